// `groom info FILE [--json]`: what a curve, mesh or scalp file holds. Curves: counts, points per
// curve, lengths, bounds, attributes. Meshes: vertices, faces by kind, shells, boundary and
// non-manifold edges, duplicate vertices, degenerate faces. Scalps (.vdb): voxel size, band, the
// mesh far queries answer from, texture coordinates, seams.
#include "cli/command.h"
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/format_table.h"
#include "kernel/io/mesh_io.h"
#include "kernel/math/polyline.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace groom::cli {
namespace {

struct Args {
    std::string input, group, grid;
    bool json = false, mesh = false, curves = false;
};

std::string num(double v)
{
    char buf[32];
    return std::string(buf, std::to_chars(buf, buf + sizeof buf, static_cast<float>(v)).ptr);
}

/// A float as JSON shows it: the shortest decimal that reads back as the same float (a float widened
/// to double would print 0.30000001192092896 for 0.3f).
double json_number(double v)
{
    return std::stod(num(v));
}

nlohmann::ordered_json json_triple(const float3& p) { return {json_number(p.x), json_number(p.y), json_number(p.z)}; }

/// min, median (mean of the two middle values for an even count), max of `v` (which it sorts).
struct Summary {
    double min = 0, median = 0, max = 0;
};
Summary summarise(std::vector<double>& v)
{
    Summary s;
    if (v.empty()) return s;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    s.min = v.front();
    s.max = v.back();
    s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    return s;
}

std::string triple(const float3& p, const char* open = "(", const char* close = ")")
{
    return open + num(p.x) + ", " + num(p.y) + ", " + num(p.z) + close;
}

void info_curves(const Args& a, const CommonOptions& common)
{
    const CurveSet cs = read_curve_input(a.input, common);
    std::vector<double> counts(cs.num_curves()), lengths(cs.num_curves());
    const auto P = cs.positions();
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const IndexRange r = cs.points_of(c);
        counts[c] = static_cast<double>(r.size());
        lengths[c] = polyline_length(P.subspan(r.begin, r.size()));
    }
    const Summary sc = summarise(counts), sl = summarise(lengths);
    const Bounds3 b = cs.bounds();
    std::ostringstream o;
    if (a.json) {
        nlohmann::ordered_json j;
        j["file"] = a.input;
        j["kind"] = "curves";
        j["curves"] = cs.num_curves();
        j["points"] = cs.num_points();
        if (cs.num_curves() > 0) {
            j["points_per_curve"] = {{"min", int64_t(sc.min)}, {"median", sc.median}, {"max", int64_t(sc.max)}};
            j["length"] = {{"min", json_number(sl.min)}, {"median", json_number(sl.median)}, {"max", json_number(sl.max)}};
        }
        if (!b.empty()) j["bounds"] = {{"min", json_triple(b.lo)}, {"max", json_triple(b.hi)}};
        j["attributes"] = nlohmann::ordered_json::array();
        for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) {
            for (const Attribute& at : cs.attributes(d).all()) {
                nlohmann::ordered_json e = {{"name", at.name}, {"domain", domain_name(d)}, {"type", type_name(at.type())}};
                if (d == Domain::Detail && at.type() == AttrType::String) e["value"] = at.values<std::string>()[0];
                j["attributes"].push_back(e);
            }
        }
        o << j.dump(2) << "\n";
    }
    else {
        o << a.input << ": curves\n";
        o << "  curves            " << cs.num_curves() << "\n";
        o << "  points            " << cs.num_points() << "\n";
        if (cs.num_curves() > 0) {
            o << "  points per curve  min " << sc.min << "  median " << sc.median << "  max " << sc.max << "\n";
            o << "  length            min " << num(sl.min) << "  median " << num(sl.median) << "  max " << num(sl.max) << "\n";
        }
        if (!b.empty()) o << "  bounds            " << triple(b.lo) << " to " << triple(b.hi) << "  size " << triple(b.size()) << "\n";
        o << "  attributes\n";
        for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) {
            for (const Attribute& at : cs.attributes(d).all()) {
                char line[160];
                std::snprintf(line, sizeof line, "    %-7s %-20s %s", domain_name(d), at.name.c_str(), type_name(at.type()));
                o << line;
                if (d == Domain::Detail) {
                    std::visit(
                        [&](const auto& v) {
                            using T = typename std::decay_t<decltype(v)>::value_type;
                            if constexpr (std::is_same_v<T, std::string>) o << " = " << nlohmann::json(v[0]).dump();
                            else if constexpr (std::is_same_v<T, float3>) o << " = " << triple(v[0]);
                            else if constexpr (std::is_same_v<T, float>) o << " = " << num(v[0]);
                            else o << " = " << v[0];
                        },
                        at.data);
                }
                o << "\n";
            }
        }
    }
    std::cout << o.str();
}

void info_mesh(const Args& a, const CommonOptions& common)
{
    const PolygonSoup soup = read_mesh(a.input, a.group);
    const std::vector<MeshGroup> groups = read_mesh_groups(a.input);
    const MeshStats s = mesh_stats(soup);
    Bounds3 b;
    for (const float3& p : soup.points) b.extend(p);
    std::ostringstream o;
    if (a.json) {
        nlohmann::ordered_json j;
        j["file"] = a.input;
        j["kind"] = "mesh";
        j["vertices"] = s.vertices;
        j["faces"] = s.faces;
        j["triangles"] = s.triangles;
        j["quads"] = s.quads;
        j["ngons"] = s.ngons;
        j["shells"] = s.shells;
        j["boundary_edges"] = s.boundary_edges;
        j["non_manifold_edges"] = s.non_manifold_edges;
        j["duplicate_vertices"] = s.duplicate_vertices;
        j["degenerate_faces"] = s.degenerate_faces;
        if (!b.empty()) j["bounds"] = {{"min", json_triple(b.lo)}, {"max", json_triple(b.hi)}};
        if (!a.group.empty()) j["group"] = a.group;
        if (!groups.empty()) {
            j["groups"] = nlohmann::ordered_json::array();
            for (const MeshGroup& g : groups) j["groups"].push_back({{"name", g.name}, {"faces", g.faces}});
        }
        o << j.dump(2) << "\n";
    }
    else {
        o << a.input << ": mesh" << (a.group.empty() ? "" : " (group " + a.group + ")") << "\n";
        o << "  vertices            " << s.vertices << "\n";
        o << "  faces               " << s.faces << " (" << s.triangles << " triangles, " << s.quads << " quads, " << s.ngons << " n-gons)\n";
        o << "  shells              " << s.shells << "\n";
        o << "  boundary edges      " << s.boundary_edges << "\n";
        o << "  non-manifold edges  " << s.non_manifold_edges << "\n";
        o << "  duplicate vertices  " << s.duplicate_vertices << "\n";
        o << "  degenerate faces    " << s.degenerate_faces << "\n";
        if (!b.empty()) o << "  bounds              " << triple(b.lo) << " to " << triple(b.hi) << "  size " << triple(b.size()) << "\n";
        o << "  (edges, shells and duplicates count vertices at identical positions as one)\n";
        // The names a --group / --scalp-group can pick.
        for (const MeshGroup& g : groups) o << "  group " << (g.name) << "  " << g.faces << " faces\n";
    }
    std::cout << o.str();
    if (s.vertices == 0) {
        // Described as it is, and said: Blender 3.4 writes such a file for a hair Curves object (a
        // trial exported the add-on's results and got a header alone, which info reported silently).
        warn(common, "info: warning: " + a.input + " holds no geometry (no vertices): did its exporter write nothing? (Blender 3.4's OBJ and PLY " +
                         "exporters write an empty file for a hair Curves object)");
    }
}

/// A .vdb scalp: what every --scalp query of it will use. Read as any command reads it (the same
/// checks, the same messages), so a file `info` describes is one the commands accept.
void info_scalp(const Args& a)
{
    const ScalpField scalp = read_scalp_vdb(a.input, nullptr, a.grid);
    const PolygonSoup mesh = scalp.mesh();
    const Bounds3 b = scalp.bounds();
    const float voxel = scalp.voxel_size(), band = scalp.band_voxels();
    const int64_t seams = scalp.seam_voxels();
    std::ostringstream o;
    if (a.json) {
        nlohmann::ordered_json j;
        j["file"] = a.input;
        j["kind"] = "scalp";
        j["grid"] = scalp.grid_name();
        j["voxel_size"] = json_number(voxel);
        j["band_voxels"] = json_number(band);
        j["active_voxels"] = scalp.active_voxels();
        if (!b.empty()) j["bounds"] = {{"min", json_triple(b.lo)}, {"max", json_triple(b.hi)}};
        j["mesh"] = {{"faces", scalp.num_faces()}, {"vertices", mesh.points.size()}, {"source", scalp.has_source_mesh() ? "stored" : "zero crossing"}};
        j["uvs"] = scalp.has_uvs();
        j["seam_voxels"] = seams;
        j["surface_tolerance"] = json_number(scalp.surface_tolerance());
        o << j.dump(2) << "\n";
    }
    else {
        // Another program's grid is named with why it was taken: what every --scalp of this file uses.
        o << a.input << ": scalp level set (grid \"" << scalp.grid_name() << "\""
          << (scalp.grid_name() == "scalp" ? "" : a.grid.empty() ? ": no grid is named \"scalp\"; the file's only float level set" : ", --scalp-grid")
          << ")\n";
        o << "  voxel size      " << num(voxel) << "\n";
        o << "  band            " << num(band) << " voxels each side (" << num(double(band) * voxel) << " scene units)\n";
        o << "  active voxels   " << scalp.active_voxels() << "\n";
        if (!b.empty()) o << "  bounds          " << triple(b.lo) << " to " << triple(b.hi) << "  size " << triple(b.size()) << "\n";
        o << "  mesh            " << scalp.num_faces() << " triangles, " << mesh.points.size() << " vertices, "
          << (scalp.has_source_mesh() ? "the repaired source mesh `groom scalp` stored (far queries exact)"
                                      : "extracted from the zero crossing (not written by `groom scalp`: far queries within about a voxel)")
          << "\n";
        o << "  uvs             " << (scalp.has_uvs() ? "yes (hair grown on it gets each root's `root_uv`)" : "no") << "\n";
        o << "  seams           "
          << (seams == 0 ? std::string("none (the band is 1-Lipschitz)")
                         : std::to_string(seams) + " voxels beside a jump of the distance (an open rim, or shells that disagree on inside; answered from the mesh)")
          << "\n";
        o << "  surface off     " << num(scalp.surface_tolerance())
          << " (75th percentile of the level set's distance at the mesh's vertices and triangle centres; hair laid on the scalp is lifted by it)\n";
    }
    std::cout << o.str();
}

bool is_vdb_path(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".vdb";
}

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("FILE", args->input, "Curves (" + curve_formats() + "), mesh (" + mesh_formats() + ") or scalp (.vdb); - = curves on stdin")
        ->required();
    app->add_flag("--json", args->json, "Print JSON instead of text");
    auto* m = app->add_flag("--mesh", args->mesh, "Read FILE as a mesh (default: decided by extension and content)");
    app->add_flag("--curves", args->curves, "Read FILE as curves")->excludes(m);
    app->add_option("--group", args->group, "OBJ mesh: describe only the faces of this object ('o') or group ('g')");
    app->add_option("--scalp-grid", args->grid, "Scalp (.vdb): the grid to describe, as --scalp-grid picks it for other commands (default: "
                                                 "the grid named 'scalp', else the file's only float level set)");
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        bool curves = args->curves;
        if (!args->curves && !args->mesh && is_vdb_path(args->input)) {
            if (!args->group.empty()) throw InvalidParam("info: --group applies to OBJ meshes; " + args->input + " is a scalp (.vdb)");
            info_scalp(*args);
            return;
        }
        if (!args->grid.empty()) throw InvalidParam("info: --scalp-grid picks a grid of a scalp (.vdb); " + args->input + " is not one");
        if (!args->curves && !args->mesh) {
            if (args->input != "-" && !is_curve_path(args->input) && !is_mesh_path(args->input)) {
                const io::Format* f = io::format_of_path(args->input);
                // ParseError, as every other command refuses a file it cannot read (exit 1, not 2).
                if (f && !f->refusal.empty()) throw ParseError("info: " + args->input + ": " + std::string(f->refusal));
                throw ParseError("info: " + args->input + ": unknown format (expected curves " + curve_formats() + ", a mesh " +
                                   mesh_formats() + " or a scalp .vdb)");
            }
            curves = holds_curves(args->input);
        }
        if (curves && !args->group.empty()) throw InvalidParam("info: --group applies to meshes; " + args->input + " holds curves");
        if (curves) info_curves(*args, common);
        else info_mesh(*args, common);
    };
}

const Registrar reg({"info", "Describe a curve, mesh or scalp file (counts, lengths, bounds, attributes, topology, voxels)", 10, setup});

}  // namespace
}  // namespace groom::cli
