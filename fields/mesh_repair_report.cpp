// RepairReport as text: the summary `groom scalp` prints and the JSON it writes with --report.
#include "fields/mesh_repair.h"

#include "kernel/error.h"

#include <cmath>
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
    line(buried_faces_removed, "faces inside another shell removed");
    if (!rim_lengths.empty()) {
        s << "  " << rim_lengths.size() << (rim_lengths.size() == 1 ? " hole (open rim)" : " holes (open rims)") << " after repair, length";
        for (size_t i = 0; i < rim_lengths.size() && i < 8; ++i) s << (i ? ", " : " ") << format_number(std::round(rim_lengths[i] * 1000.0) / 1000.0);
        if (rim_lengths.size() > 8) s << ", ... (" << rim_lengths.size() - 8 << " more)";
        s << "\n";
    }
    if (holes_filled) s << "  " << holes_filled << (holes_filled == 1 ? " hole" : " holes") << " filled (" << faces_added_by_fill << " faces)\n";
    if (holes_left_open) {
        s << "  " << holes_left_open << (holes_left_open == 1 ? " rim" : " rims")
          << " within the fill length left open: a rim that meets another at a vertex, or one no patch fits without repeating "
             "an edge of the mesh\n";
    }
    if (rims_inside_union) {
        s << "  " << rims_inside_union << (rims_inside_union == 1 ? " rim" : " rims")
          << " where buried faces went (inside the union: not holes, never filled)\n";
    }
    if (flipped_by_user) s << "  all faces flipped (--flip)\n";
    for (const std::string& n : notes) s << "  note: " << n << "\n";
    std::string out = s.str();
    if (!out.empty()) out.pop_back();
    return out;
}

}  // namespace groom
