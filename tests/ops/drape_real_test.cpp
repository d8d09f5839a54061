// Hair pushed out of the scalp point by point folded back where it ran through a thin part (Sintel's
// ears) and was laid again over it (fields/drape_runs.h, tested on a sphere in
// tests/fields/drape_runs_test.cpp). Here, on Sintel's head: the turns of generate's hair and of
// cull's pushed guides.
#include "fields/scalp_field.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "ops/cull.h"
#include "ops/generate.h"
#include "support/curve_turns.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace groom;
using groom::test::largest_turns;
using groom::test::Turn;

namespace {

/// Sintel's head as a field and her 228 guides, read once for the tests here.
struct Sintel {
    ScalpField field;
    CurveSet guides;
};
const Sintel& sintel(const std::string& head, const std::string& guides)
{
    static const Sintel s{build_scalp(read_mesh(head)), read_curves(guides)};
    return s;
}

}  // namespace

TEST(GenerateReal, HairAtSintelsEarsDoesNotFoldBack)
{
    GROOM_REQUIRE_SHARED(head, "sintel_tressfx_opengl/sintel.obj");
    GROOM_REQUIRE_SHARED(guides_path, "sintel_tressfx_opengl/sintel_guides.obj");
    // Blends of guides that pass either side of an ear run through the ear flap. Pushed out point
    // by point, 77 of 15,000 hairs folded back by more than 90 degrees at the ears (up to 177), where
    // none of Sintel's guides turns by more than 53. Laid over the ear, 8 are left (runs whose every
    // way out turns as much). The eye sockets (open: the field's sign is not settled inside them)
    // and a blend of opposite guides at the crown keep theirs: at most 40 more in all.
    const auto& [field, guides] = sintel(head, guides_path);
    for (const Turn& t : largest_turns(guides)) ASSERT_LT(t.degrees, 60.0);
    GenerateParams params;
    params.count = 15000;
    const CurveSet hair = generate(guides, field, scalp_root_sampler(field), params);
    int64_t at_ears = 0, elsewhere = 0;
    for (const Turn& t : largest_turns(hair)) {
        if (!(t.degrees > 90.0)) continue;
        // The ears stand out at |x| > 5.5 behind the face (z < 5) below y = 36; the eyes are at z > 6.
        const bool ear = std::fabs(t.at.x) > 5.5f && t.at.z < 5.0f && t.at.y < 36.0f;
        (ear ? at_ears : elsewhere) += 1;
    }
    EXPECT_LE(at_ears, 12);
    EXPECT_LE(elsewhere, 40);
}

TEST(CullReal, PushingSintelsGuidesOutFoldsNone)
{
    GROOM_REQUIRE_SHARED(head, "sintel_tressfx_opengl/sintel.obj");
    GROOM_REQUIRE_SHARED(guides_path, "sintel_tressfx_opengl/sintel_guides.obj");
    // Her guides dip into the head in places (0.9% of their points); pushed out to a 0.1 clearance
    // point by point, 2 of the 228 folded back by more than 90 degrees (none does before).
    const auto& [field, guides] = sintel(head, guides_path);
    for (const Turn& t : largest_turns(guides)) ASSERT_LT(t.degrees, 60.0);
    CullParams params;
    params.mode = CullMode::Push;
    params.clearance = 0.1f;
    CullStats stats;
    const CurveSet pushed = cull(guides, field, params, &stats);
    EXPECT_GT(stats.points_pushed, 50);
    for (const Turn& t : largest_turns(pushed)) EXPECT_LE(t.degrees, 90.0);
}
