// RepairReport as text: the summary `groom scalp` prints and the JSON it writes with --report.
#include "fields/mesh_repair.h"

#include <sstream>

namespace groom {

std::string RepairReport::summary() const
{
    std::ostringstream s;
    auto line = [&](int64_t n, const char* what) {
        if (n) s << "  " << n << " " << what << "\n";
    };
    s << "repair: " << input_vertices << " vertices, " << input_faces << " faces in; " << output_vertices << " vertices, "
      << output_faces << " triangles out\n";
    line(duplicate_vertices_merged, "duplicate vertices merged");
    line(degenerate_faces_removed, "degenerate faces removed");
    line(duplicate_faces_removed, "duplicate faces removed");
    line(pinched_faces_split, "pinched faces split");
    line(isolated_vertices_removed, "unused vertices removed");
    line(ngons_triangulated, "quads/n-gons triangulated");
    line(non_manifold_edges, "non-manifold edges cut");
    line(non_manifold_vertices, "non-manifold vertices split");
    line(faces_flipped, "faces flipped to a consistent, outward winding");
    s << "  " << shells << " shells (" << closed_shells << " closed), " << boundary_loops << " boundary loops\n";
    line(shells_flipped, "shells turned outward");
    line(enclosed_shells_removed, "enclosed shells removed");
    if (flipped_by_user) s << "  all faces flipped (--flip)\n";
    for (const std::string& n : notes) s << "  note: " << n << "\n";
    std::string out = s.str();
    if (!out.empty()) out.pop_back();
    return out;
}

std::string RepairReport::to_json() const
{
    std::ostringstream s;
    s << "{\n";
    auto field = [&](const char* k, int64_t v) { s << "  \"" << k << "\": " << v << ",\n"; };
    field("input_vertices", input_vertices);
    field("input_faces", input_faces);
    field("duplicate_vertices_merged", duplicate_vertices_merged);
    field("degenerate_faces_removed", degenerate_faces_removed);
    field("duplicate_faces_removed", duplicate_faces_removed);
    field("pinched_faces_split", pinched_faces_split);
    field("isolated_vertices_removed", isolated_vertices_removed);
    field("ngons_triangulated", ngons_triangulated);
    field("triangles_from_ngons", triangles_from_ngons);
    field("non_manifold_edges", non_manifold_edges);
    field("non_manifold_vertices", non_manifold_vertices);
    field("vertices_added_by_split", vertices_added_by_split);
    field("faces_flipped", faces_flipped);
    field("shells", shells);
    field("closed_shells", closed_shells);
    field("shells_flipped", shells_flipped);
    field("enclosed_shells_removed", enclosed_shells_removed);
    field("faces_in_removed_shells", faces_in_removed_shells);
    field("boundary_loops", boundary_loops);
    field("output_vertices", output_vertices);
    field("output_faces", output_faces);
    s << "  \"flipped_by_user\": " << (flipped_by_user ? "true" : "false") << ",\n  \"notes\": [";
    for (size_t i = 0; i < notes.size(); ++i) {
        s << (i ? ", " : "") << '"';
        for (char c : notes[i]) {
            if (c == '"' || c == '\\') s << '\\';
            s << c;
        }
        s << '"';
    }
    s << "],\n  \"shell_list\": [";
    for (size_t i = 0; i < shell_list.size(); ++i) {
        const Shell& sh = shell_list[i];
        s << (i ? ",\n    " : "\n    ") << "{\"faces\": " << sh.faces << ", \"area\": " << sh.area << ", \"closed\": " << (sh.closed ? "true" : "false")
          << ", \"flipped\": " << (sh.flipped ? "true" : "false") << ", \"removed\": " << (sh.removed ? "true" : "false")
          << ", \"winding\": " << sh.winding << ", \"bbox\": [" << sh.lo[0] << ", " << sh.lo[1] << ", " << sh.lo[2] << ", " << sh.hi[0]
          << ", " << sh.hi[1] << ", " << sh.hi[2] << "]}";
    }
    s << "\n  ]\n}\n";
    return s.str();
}

}  // namespace groom
