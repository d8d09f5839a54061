#include "fields/source_mesh.h"

#include "fields/metadata_text.h"
#include "kernel/error.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace groom::detail {

std::string encode_source_mesh(std::span<const float3> points, std::span<const std::array<int32_t, 3>> tris)
{
    std::string out = "groom-source-mesh 1 " + std::to_string(points.size()) + " " + std::to_string(tris.size()) + "\n";
    out.reserve(out.size() + points.size() * 36 + tris.size() * 21);
    char buf[32];
    auto num = [&](auto x, char sep) {
        const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
        out.append(buf, end);
        out += sep;
    };
    for (const float3& p : points) num(p.x, ' '), num(p.y, ' '), num(p.z, '\n');
    for (const auto& t : tris) num(t[0], ' '), num(t[1], ' '), num(t[2], '\n');
    return out;
}

SourceMesh decode_source_mesh(std::string_view text, const std::string& what)
{
    MetadataText in(text, what + ": source mesh (grid metadata 'groom_source_mesh')");
    in.header("groom-source-mesh");
    const int64_t np = in.count(3, "a point count");
    const int64_t nt = in.count(1, "a triangle count");
    in.expect_numbers(np * 3 + nt * 3);
    SourceMesh mesh;
    mesh.points.resize(size_t(np));
    for (float3& p : mesh.points) p.x = in.real(), p.y = in.real(), p.z = in.real();
    mesh.tris.resize(size_t(nt));
    for (auto& t : mesh.tris) {
        for (int k = 0; k < 3; ++k) t[k] = int32_t(in.integer(0, np - 1, "a vertex index"));
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
            in.fail("triangle " + std::to_string(&t - mesh.tris.data()) + " repeats a corner (" + std::to_string(t[0]) + " " +
                 std::to_string(t[1]) + " " + std::to_string(t[2]) + ")");
        }
    }
    if (!in.token().empty()) in.fail("unexpected text after the last triangle");
    // Each directed edge once: the pseudo-normals pair every edge side with one face.
    std::vector<std::pair<int32_t, int32_t>> edges;
    edges.reserve(mesh.tris.size() * 3);
    for (const auto& t : mesh.tris)
        for (int k = 0; k < 3; ++k) edges.emplace_back(t[k], t[(k + 1) % 3]);
    std::sort(edges.begin(), edges.end());
    const auto dup = std::adjacent_find(edges.begin(), edges.end());
    if (dup != edges.end()) {
        in.fail("the edge " + std::to_string(dup->first) + " -> " + std::to_string(dup->second) +
             " belongs to two triangles; expected an oriented manifold mesh");
    }
    return mesh;
}

}  // namespace groom::detail
