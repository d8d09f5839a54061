// `groom scalp`: repair a mesh and convert it to the scalp level set (fields/scalp_field.h).
#include "cli/command.h"
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/atomic_file.h"
#include "kernel/io/mesh_io.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

namespace groom::cli {
namespace {

/// The repair report as `--report FILE.json` writes it: every count, the notes, one object per shell.
std::string repair_report_json(const RepairReport& r)
{
    nlohmann::ordered_json j;
    const std::pair<const char*, int64_t> counts[] = {
        {"input_vertices", r.input_vertices},
        {"input_faces", r.input_faces},
        {"duplicate_vertices_merged", r.duplicate_vertices_merged},
        {"degenerate_faces_removed", r.degenerate_faces_removed},
        {"duplicate_faces_removed", r.duplicate_faces_removed},
        {"pinched_faces_split", r.pinched_faces_split},
        {"isolated_vertices_removed", r.isolated_vertices_removed},
        {"ngons_triangulated", r.ngons_triangulated},
        {"triangles_from_ngons", r.triangles_from_ngons},
        {"non_manifold_edges", r.non_manifold_edges},
        {"non_manifold_vertices", r.non_manifold_vertices},
        {"vertices_added_by_split", r.vertices_added_by_split},
        {"faces_flipped", r.faces_flipped},
        {"shells", r.shells},
        {"closed_shells", r.closed_shells},
        {"shells_flipped", r.shells_flipped},
        {"enclosed_shells_removed", r.enclosed_shells_removed},
        {"faces_in_removed_shells", r.faces_in_removed_shells},
        {"buried_faces_removed", r.buried_faces_removed},
        {"shells_with_buried_faces", r.shells_with_buried_faces},
        {"boundary_loops", r.boundary_loops},
        {"holes_filled", r.holes_filled},
        {"faces_added_by_fill", r.faces_added_by_fill},
        {"holes_left_open", r.holes_left_open},
        {"rims_inside_union", r.rims_inside_union},
        {"buried_shells_removed", r.buried_shells_removed},
        {"output_vertices", r.output_vertices},
        {"output_faces", r.output_faces},
    };
    for (const auto& [key, value] : counts) j[key] = value;
    j["rim_lengths"] = r.rim_lengths;
    j["flipped_by_user"] = r.flipped_by_user;
    j["notes"] = r.notes;
    j["shell_list"] = nlohmann::ordered_json::array();
    for (const RepairReport::Shell& sh : r.shell_list) {
        j["shell_list"].push_back({{"faces", sh.faces},
                                   {"area", sh.area},
                                   {"closed", sh.closed},
                                   {"flipped", sh.flipped},
                                   {"removed", sh.removed},
                                   {"winding", sh.winding},
                                   {"buried_faces", sh.buried_faces},
                                   {"source", sh.source},
                                   {"bbox", {sh.lo[0], sh.lo[1], sh.lo[2], sh.hi[0], sh.hi[1], sh.hi[2]}}});
    }
    return j.dump(2) + "\n";
}

std::string box_text(const Bounds3& b)
{
    return "(" + format_number(b.lo.x) + ", " + format_number(b.lo.y) + ", " + format_number(b.lo.z) + ") to (" + format_number(b.hi.x) +
           ", " + format_number(b.hi.y) + ", " + format_number(b.hi.z) + ")";
}

struct Args {
    std::vector<std::string> inputs;
    std::string output, report;
    float voxel = 0.0f;
    bool keep_enclosed = false;
    ScalpBuildParams params;
};

/// The meshes read and joined into one soup. --group picks the head's faces out of the first mesh;
/// the others (its eyeballs, teeth, a body) are whole, and each must come within half the first
/// one's size of its box and be within 200x of its size: a mesh in other units or from another
/// scene's placement would otherwise be accepted without a word (a trial joined Sintel's head in
/// metres to her eyeballs in centimetres, 80 head-sizes away, and the voxel, sized to fit both,
/// left the head 3 voxels across; her head in centimetres with her eyes in metres put 5 mm eyes
/// under the bust, 450x smaller than the head). With several meshes and no --voxel,
/// the first one sets the automatic voxel (its own diagonal / 256): a body joined to a head does
/// not make the head coarser.
constexpr float kMaxSizeRatio = 200.0f;  // centimetres against metres is 100x the head's size ratio to its eyes

PolygonSoup joined_meshes(Args& a, bool voxel_given, const CommonOptions& common)
{
    PolygonSoup soup;
    Bounds3 first;
    std::string sizes;
    for (size_t k = 0; k < a.inputs.size(); ++k) {
        PolygonSoup mesh;
        try {
            mesh = read_mesh(a.inputs[k], k == 0 ? a.params.group : std::string());
        } catch (const ParseError& e) {
            if (k != 0 || a.inputs.size() < 2 || a.params.group.empty()) throw;
            throw ParseError(std::string(e.what()) + " (--group picks faces of the first MESH only; the others are joined whole)");
        }
        Bounds3 box;
        for (const float3& p : mesh.points) box.extend(p);
        if (k == 0) {
            first = box;
        } else {
            const float across = length(first.size()), its = length(box.size());
            const float3 grow(0.5f * across, 0.5f * across, 0.5f * across);
            const float3 lo = max(first.lo - grow, box.lo), hi = min(first.hi + grow, box.hi);
            const bool apart = !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z);
            const bool scale = its > kMaxSizeRatio * across || across > kMaxSizeRatio * its;
            if (apart || scale) {
                throw InvalidGeometry("scalp: " + a.inputs[k] + " (bounds " + box_text(box) + ", " + format_number(its) + " units across) " +
                                      (apart ? "lies away from " : "is of another scale than ") + a.inputs[0] + " (" + box_text(first) +
                                      ", " + format_number(across) + " units across" +
                                      (apart ? "): a mesh joined to the head must touch it, or come within half its size"
                                             : "): a mesh joined to the head is within " + format_number(kMaxSizeRatio) + "x of its size") +
                                      " (eyeballs, teeth, a body). Other units or another scene's placement? Scale or move it to "
                                      "the head in the program that made it, or, if it really is so, join the two in one file");
            }
        }
        sizes += (sizes.empty() ? "" : ", ") + a.inputs[k] + " " + std::to_string(mesh.num_faces()) + " faces";
        // With several meshes each shell's source in the report names its file too.
        if (a.inputs.size() > 1) {
            const std::string file = std::filesystem::path(a.inputs[k]).filename().string();
            if (!mesh.has_parts()) mesh.part_names = {std::string()}, mesh.face_part.assign(mesh.num_faces(), 0);
            for (std::string& name : mesh.part_names) name = name.empty() ? file : file + ": " + name;
        }
        append(soup, mesh, a.params.source);
    }
    if (a.inputs.size() > 1) {
        if (!voxel_given) a.params.voxel_size = length(first.size()) / 256.0f;
        note(common, "scalp: " + std::to_string(a.inputs.size()) + " meshes joined (" + sizes + ")" +
                         (voxel_given ? "" : "; voxel from the first one's diagonal / 256"));
    }
    return soup;
}

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("MESH", args->inputs,
                    "Head or scalp mesh (" + mesh_formats() + "); any units, any mess. Several are joined into one surface: "
                    "a head with open eye sockets and its eyeballs, so hair does not fall into the sockets")
        ->required();
    app->add_option("-o,--output", args->output, "Output level set (.vdb, grid 'scalp')")->required();
    CLI::Option* voxel = app->add_option("--voxel", args->voxel, "Voxel size, scene units (> 0; default: bounding-box diagonal / 256)");
    app->add_option("--band", args->params.band_voxels, "Narrow-band half width in voxels (1..64)")->capture_default_str();
    app->add_flag("--flip", args->params.flip, "The mesh is inside out: swap inside and outside");
    app->add_option("--report", args->report, "Write the repair report as JSON to this file");
    app->add_option("--group", args->params.group,
                    "OBJ mesh: only the faces of this object ('o') or group ('g'), e.g. the head without eyes, teeth and hair proxies "
                    "(of the first MESH where there are several)");
    app->add_option("--fill-holes", args->params.fill_holes,
                    "Close the mesh's open rims up to this length, scene units (eye sockets and a mouth with no eyeballs or "
                    "teeth to join, not the neck): hair then lies over them instead of falling in. The rims' lengths are "
                    "printed; 0 = none")
        ->capture_default_str();
    app->add_flag("--keep-enclosed", args->keep_enclosed, "Keep shells that lie inside another (eyes, teeth) and the faces of overlapping shells that lie inside another (an eyeball's back); removed by default");
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, voxel, &common] {
        Args& a = *args;
        for (const std::string& in : a.inputs) {
            if (std::filesystem::path(in).extension() == ".vdb") {
                throw InvalidParam("scalp: " + in + " is a .vdb, a scalp field already (expected a mesh, " + mesh_formats() +
                                   "): give it to the other commands as --scalp " + in);
            }
        }
        check_outputs({{"-o", a.output}, {"--report", a.report}}, std::span<const std::string>(a.inputs), common);
        for (size_t k = 1; k < a.inputs.size(); ++k) {
            for (size_t j = 0; j < k; ++j) {
                if (names_one_file(a.inputs[j], a.inputs[k])) {
                    throw InvalidParam("scalp: " + a.inputs[k] + " is given twice (as MESH " + std::to_string(j + 1) + " and " +
                                       std::to_string(k + 1) + "): joined with itself it would be two coincident surfaces");
                }
            }
        }
        if (std::filesystem::path(a.output).extension() != ".vdb" && !written_in_place(a.output)) {
            throw InvalidParam("scalp: -o must name a .vdb file (got '" + a.output + "')");
        }
        if (voxel->count() > 0 && !(a.voxel > 0.0f)) {
            throw InvalidParam("scalp: --voxel must be > 0 (got " + std::to_string(a.voxel) + "); omit it for an automatic size");
        }
        a.params.voxel_size = a.voxel;
        a.params.for_queries = false;  // written, never queried: no query bricks in the estimate
        a.params.remove_enclosed_shells = !a.keep_enclosed;
        a.params.source.clear();
        for (const std::string& in : a.inputs) a.params.source += (a.params.source.empty() ? "" : " + ") + in;
        a.params.validate();

        const auto start = std::chrono::steady_clock::now();
        const PolygonSoup soup = joined_meshes(a, voxel->count() > 0, common);
        auto progress = make_progress(common);
        RepairReport report;
        const ScalpField scalp = build_scalp(soup, a.params, &report, progress.get());
        note(common, report.summary());
        // The grid and the report land together, or neither.
        OutputBatch outputs;
        write_scalp(scalp, a.output, outputs);
        if (!a.report.empty()) outputs.open(a.report, false) << repair_report_json(report);
        outputs.commit();
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char buf[256];
        std::snprintf(buf, sizeof buf, "scalp: voxel %.4g, band %g voxels, %lld triangles -> %s (%.2f s)", scalp.voxel_size(),
                      double(scalp.band_voxels()), static_cast<long long>(scalp.num_faces()), a.output.c_str(), secs);
        note(common, buf);
    };
}

const Registrar reg({"scalp", "Repair a head mesh and convert it to a signed-distance level set (.vdb)", 100, setup});

}  // namespace
}  // namespace groom::cli
