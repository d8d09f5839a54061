// Mesh repair report: what `build_scalp` did to a user's mesh before converting it, in counts.
// Nothing is dropped silently: every removed face, merged vertex and removed shell is counted here,
// printed by `groom scalp` on stderr and written by `--report FILE.json`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace groom {

struct RepairReport {
    int64_t input_vertices = 0, input_faces = 0;
    int64_t duplicate_vertices_merged = 0;   ///< vertices at exactly the position of another, welded
    int64_t degenerate_faces_removed = 0;    ///< < 3 distinct vertices, or zero area
    int64_t duplicate_faces_removed = 0;     ///< the same vertex set as another face
    int64_t pinched_faces_split = 0;         ///< polygons that visit one position twice, split in two
    int64_t isolated_vertices_removed = 0;   ///< vertices used by no face
    int64_t ngons_triangulated = 0;          ///< faces with 4+ vertices
    int64_t triangles_from_ngons = 0;        ///< triangles those became
    int64_t non_manifold_edges = 0;          ///< edges with 3+ faces (or inconsistent), cut apart
    int64_t non_manifold_vertices = 0;       ///< vertices whose faces form several fans, split
    int64_t vertices_added_by_split = 0;     ///< vertex copies made to split them
    int64_t faces_flipped = 0;               ///< faces whose winding was reversed (net, vs. the input)
    int64_t shells = 0;                      ///< connected components after repair (before removal)
    int64_t closed_shells = 0;               ///< of which closed (no boundary edge)
    int64_t shells_flipped = 0;              ///< shells turned so their normals face outwards
    int64_t enclosed_shells_removed = 0;     ///< shells entirely inside a larger shell (eyes, teeth, helpers)
    int64_t faces_in_removed_shells = 0;
    int64_t buried_faces_removed = 0;        ///< faces of overlapping shells lying inside another shell
    int64_t shells_with_buried_faces = 0;
    int64_t buried_shells_removed = 0;       ///< of those, shells buried whole (listed as removed)
    int64_t boundary_loops = 0;              ///< holes / open rims, counted before shells and buried faces go
    std::vector<double> rim_lengths;         ///< every hole of the repaired mesh (before filling), longest first
    int64_t rims_inside_union = 0;           ///< rims cut where buried faces went: inside the union, not holes
    int64_t holes_filled = 0;                ///< rims closed by `fill_holes`
    int64_t holes_left_open = 0;             ///< rims within `fill_holes` left open (pinched, or no patch fits)
    int64_t faces_added_by_fill = 0;
    int64_t output_vertices = 0, output_faces = 0;
    bool flipped_by_user = false;            ///< --flip was given
    std::vector<std::string> notes;          ///< sentences for the user (why a shell went, etc.)

    /// Every shell after repair, largest area first.
    struct Shell {
        int64_t faces = 0;
        double area = 0.0;           ///< scene units^2
        float lo[3]{}, hi[3]{};      ///< bounding box
        bool closed = false, flipped = false, removed = false;
        double winding = 0.0;        ///< largest |winding number| of its samples w.r.t. a larger shell
        int64_t buried_faces = 0;    ///< faces removed as lying inside another shell
        /// The file's part most of its faces came from (an OBJ object or group; with several meshes
        /// joined, "file: part" or the file), "(+N more parts)" when it joins others; "" unnamed.
        std::string source;
    };
    std::vector<Shell> shell_list;

    /// One line per non-zero count, for stderr.
    std::string summary() const;
};

}  // namespace groom
