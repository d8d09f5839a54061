// The same scalp field for a head in any pose (issue 21): a mesh moved, turned and scaled (the voxel
// scaled with it) answers, mapped back, what the original answers: the same repair, distances
// within a fraction of a voxel, and no sign that changes farther than half a voxel from the
// surface. A user who exports the head in another pose, or a rig that rebuilds the field every
// frame, gets the same hair. Checked on messy copies of an analytic sphere and on every real head.
#include "fields/scalp_field.h"
#include "kernel/io/mesh_io.h"
#include "kernel/rng.h"
#include "support/similarity.h"
#include "support/sphere_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ostream>
#include <vector>

namespace groom {
namespace {

struct PoseDifference {
    double p99 = 0.0;              ///< 99th percentile of |difference|, voxels
    double worst = 0.0;            ///< largest |difference|, voxels
    int64_t far_sign_changes = 0;  ///< sign differs and both answers are more than h/2 from 0
};

/// `n` probes near the surface of `base` (area-uniform on its mesh, each moved up to 3 voxels in a
/// random direction), asked of `base` and, moved by `motion`, of `moved`; distances mapped back.
PoseDifference compare(const ScalpField& base, const ScalpField& moved, const Similarity& motion, int n, uint64_t seed)
{
    const float h = base.voxel_size();
    const std::vector<SurfaceSample> on = base.sample_ball({}, 0.0f, n, seed);
    std::vector<double> diff;
    PoseDifference out;
    for (size_t i = 0; i < on.size(); ++i) {
        Rng rng(seed, uint64_t(i), 1);
        float3 dir;
        do dir = float3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        while (length(dir) > 1.0f || length(dir) < 0.1f);
        const float3 p = on[i].position + normalize(dir) * (3.0f * h * rng.uniform());
        const float d0 = base.distance(p), d1 = float(double(moved.distance(motion.apply(p))) / motion.scale);
        diff.push_back(std::fabs(double(d1) - double(d0)) / h);
        out.far_sign_changes += ((d0 < 0.0f) != (d1 < 0.0f)) && std::min(std::fabs(d0), std::fabs(d1)) > 0.5f * h;
    }
    std::sort(diff.begin(), diff.end());
    out.p99 = diff[diff.size() * 99 / 100];
    out.worst = diff.back();
    return out;
}

/// The repair's decisions, which must not depend on the pose. All but one are exact: a buried face
/// (all three vertices inside another shell, |winding number| > 1/2) whose vertex lies on the other
/// shell's surface to within float rounding can go either way. ICT's 52 overlapping shells have
/// about 35 vertices within 0.001 of the threshold, and a pose moved one of them across it (one face
/// of 11,124). Such a face lies on the union's surface either way, so the field does not change
/// (the distances are compared below). At most 1 in 2,000 faces may differ, and only those.
void expect_same_repair(const RepairReport& a, const RepairReport& b)
{
    EXPECT_EQ(a.degenerate_faces_removed, b.degenerate_faces_removed);
    EXPECT_EQ(a.non_manifold_edges, b.non_manifold_edges);
    EXPECT_EQ(a.shells_flipped, b.shells_flipped);
    EXPECT_EQ(a.enclosed_shells_removed, b.enclosed_shells_removed);
    EXPECT_EQ(a.faces_in_removed_shells, b.faces_in_removed_shells);
    EXPECT_EQ(a.boundary_loops, b.boundary_loops);
    const int64_t buried = std::abs(a.buried_faces_removed - b.buried_faces_removed);
    EXPECT_LE(buried, a.input_faces / 2000) << "buried faces " << a.buried_faces_removed << " and " << b.buried_faces_removed;
    EXPECT_LE(std::abs(a.faces_flipped - b.faces_flipped), buried);
    EXPECT_EQ(a.output_faces + a.buried_faces_removed, b.output_faces + b.buried_faces_removed);
}

/// Builds `soup` as it is (voxel h, 0 = automatic) and moved by each of `poses` random
/// similarities; expects the same repair and differences within `p99_max` voxels with at most
/// `far_max` sign changes farther than h/2.
ScalpField check_poses(const PolygonSoup& soup, float h, int poses, uint64_t seed, double p99_max, int64_t far_max)
{
    ScalpBuildParams params;
    params.voxel_size = h;
    RepairReport report;
    ScalpField base = build_scalp(soup, params, &report);
    for (int k = 0; k < poses; ++k) {
        const Similarity motion = Similarity::random(seed + uint64_t(k), 0.05, 20.0, 100.0);
        ScalpBuildParams moved_params;
        moved_params.voxel_size = float(double(base.voxel_size()) * motion.scale);
        RepairReport moved_report;
        const ScalpField moved = build_scalp(motion.apply(soup), moved_params, &moved_report);
        SCOPED_TRACE(testing::Message() << "pose " << k << ", scale " << motion.scale);
        expect_same_repair(report, moved_report);
        const PoseDifference d = compare(base, moved, motion, 3000, seed * 31 + uint64_t(k));
        EXPECT_LE(d.p99, p99_max) << "largest " << d.worst << " voxels";
        EXPECT_LE(d.far_sign_changes, far_max);
    }
    return base;
}

// Messy copies of a sphere: split seams, flipped faces, quads, a hexagon, degenerate triangles, a
// non-manifold fin, a hole (an opening whose winding-number seam the field must not interpolate
// across) and an enclosed eye. Measured: p99 0.016-0.017 voxels, largest 0.06, no sign change.
TEST(ScalpPose, MessySphereGivesTheSameFieldInAnyPose)
{
    const float3 c(-1, 0.5f, 2);
    const float R = 1.5f;
    const PolygonSoup dirty = messy_uv_sphere(uv_sphere(c, R, 24, 48), 24, 48, c, R);
    check_poses(dirty, R / 60.0f, 3, 7, 0.25, 0);
}

struct Head {
    const char* path;
    double p99_max;    ///< voxels
    int64_t far_max;   ///< sign changes farther than h/2 of 3,000 probes
    bool lipschitz;    ///< closed, and no sheets that disagree: keep_outside may bound by distance
};

void PrintTo(const Head& head, std::ostream* os) { *os << head.path; }

class ScalpPoseReal : public testing::TestWithParam<Head> {};

// Every real head at its default voxel, in one random pose. The aim (p99 <= 0.25 voxel, no sign
// change farther than h/2) holds on all; makehuman has a looser limit, as its helper surfaces
// (tights, skirt) lie within a voxel of the body: sheets closer than a voxel, which no grid of that
// voxel resolves, so what it reads between them depends on where the voxels fall. Measured p99
// (voxels), since the faces of overlapping shells buried inside another are removed: ponytail 0.10,
// demosthenes 0.077, ICT 0.21, Lee Perry-Smith 0.066, makehuman 0.24 (0.89 largest, no sign
// change), nefertiti 0.076, Ratboy 0.067, Sintel 0.080, Sintel's collider 0.040. Before that,
// ponytail 0.12 and makehuman 0.39 with one sign change (the body's faces inside the tights made a
// third sheet); before the shell work, ponytail 0.25, ICT 0.37, makehuman 0.6 with 104 or 105
// shells removed by pose.
//
// The sign-change limits are not all 0 because a pose moved by float rounding (scale x (1 +- 1e-6),
// translation +- 1e-5: what another CPU's libm or another compiler gives for the same random pose)
// moves a probe or two across an eyelid, lip or nostril crease thinner than a voxel. Measured over 30
// such neighbours of this pose: ICT up to 2 sign changes (0.5-1.6 voxels out, eyes and mouth), Lee
// Perry-Smith 1, makehuman 1, Sintel 1 (0.51 voxel, her eyelid; CI's machine found it at this very
// pose); p99 up to ICT 0.238. The other five heads: none in all 30.
TEST_P(ScalpPoseReal, SameFieldInAnyPose)
{
    const Head head = GetParam();
    GROOM_REQUIRE_SHARED(path, head.path);
    const ScalpField field = check_poses(read_mesh(path), 0.0f, 1, 11, head.p99_max, head.far_max);
    // Closed heads keep keep_outside's distance bound. Nefertiti did not until voxels whose closest
    // face the walk had got wrong were measured again (40 of them read as seams); Lee Perry-Smith is
    // closed but its folded quads make sheets that disagree.
    EXPECT_EQ(field.lipschitz(), head.lipschitz);
}

INSTANTIATE_TEST_SUITE_P(Heads, ScalpPoseReal,
                         testing::Values(Head{"amd_tressfx_ponytail/ponytail_head.obj", 0.25, 0, false},
                                         Head{"demosthenes_scan/demosthenes-low-res.obj", 0.25, 0, false},
                                         Head{"ict_facekit/generic_neutral_mesh.obj", 0.25, 3, false},
                                         Head{"lee_perry_smith/LeePerrySmith.obj", 0.25, 1, false},
                                         Head{"makehuman/base.obj", 0.35, 2, false},
                                         Head{"nefertiti_scan/nefertiti-lowres.obj", 0.25, 0, true},
                                         Head{"ratboy_mohawk_tressfx/Ratboy_body.obj", 0.25, 0, true},
                                         Head{"sintel_tressfx_opengl/sintel.obj", 0.25, 1, false},
                                         Head{"sintel_frostbitten/sintel-collider.obj", 0.25, 0, true}),
                         [](const testing::TestParamInfo<Head>& info) {
                             std::string name = info.param.path;
                             name = name.substr(name.find('/') + 1);
                             name = name.substr(0, name.find('.'));
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

}  // namespace
}  // namespace groom
