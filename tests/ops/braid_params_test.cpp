// Tests for BraidParams validation (ops/braid.cpp): every invalid option and every option that needs
// a scalp or another option is rejected with a message naming it, the valid range and the value.
#include "ops/braid.h"

#include "kernel/error.h"
#include "tests/ops/make_curves.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>

using namespace groom;
using groom::test::make_curves;

namespace {

std::string message_of(const std::function<void()>& fn)
{
    try {
        fn();
    }
    catch (const InvalidParam& e) {
        return e.what();
    }
    return "(no InvalidParam thrown)";
}

}  // namespace

TEST(Braid, RejectsInvalidOptions)
{
    {
        const CurveSet g = make_curves({{{0, 0, 0}, {0, 1, 0}}});
        const auto msg = [&](BraidParams p) { return message_of([&] { braid(g, p); }); };
        BraidParams p;
        p.pattern = BraidPattern::Fishtail;
        p.strands = 5;
        EXPECT_EQ(msg(p), "braid: `pattern` fishtail needs an even `strands` >= 4 (got `strands` 5)");
        p.pattern = BraidPattern::Twist;
        p.strands = 3;
        EXPECT_EQ(msg(p), "braid: `pattern` twist has 2 strands; use `pattern` rope for more (got `strands` 3)");
        p = BraidParams{};
        p.pattern = BraidPattern::Lissajous;
        p.hand = BraidHand::Under;
        EXPECT_NE(msg(p).find("`hand` does not apply to `pattern` lissajous"), std::string::npos);
        p = BraidParams{};
        p.flyaways = 0.1f;
        EXPECT_EQ(msg(p), "braid: `flyaways` moves fibers; give `fibers` M > 0");
        p.fibers = 4;
        p.flyaways = 1.5f;
        EXPECT_EQ(msg(p), "braid: `flyaways` must be a fraction in [0, 1] (got 1.5)");
        p = BraidParams{};
        p.fibers = 4;
        p.feed_in = 1.0f;
        EXPECT_EQ(msg(p), "braid: `feed_in` must be a fraction in [0, 1) (got 1)");
        p = BraidParams{};
        p.tie = 1.5f;
        EXPECT_EQ(msg(p), "braid: `tie` must be an arc-length fraction in [0, 1] (got 1.5)");
        p = BraidParams{};
        p.tie_turns = 0;
        EXPECT_EQ(msg(p), "braid: `tie_turns` must be in [1, 64] (got 0)");
        p = BraidParams{};
        p.flatten = 0.95f;
        EXPECT_EQ(msg(p), "braid: `flatten` must be in [0, 0.9] (got 0.95)");
        p = BraidParams{};
        p.loose_length = -1.0f;
        EXPECT_EQ(msg(p), "braid: `loose_length` must be a finite number >= 0 and <= 1e+15 (got -1)");
        p = BraidParams{};
        p.flare = std::numeric_limits<float>::infinity();
        EXPECT_EQ(msg(p), "braid: `flare` must be a finite number >= 0 and <= 100 (got inf)");
    }
    const CurveSet guides = make_curves({{{0, 0, 0}, {0, 1, 0}}});
    const auto rejects = [&](BraidParams p, const std::string& expected) {
        const std::string msg = message_of([&] { braid(guides, p); });
        EXPECT_NE(msg.find(expected), std::string::npos) << "got: " << msg << "\nexpected: " << expected;
    };
    BraidParams p;
    p.strands = 1;
    rejects(p, "braid: `strands` must be >= 2 (got 1)");
    p = {};
    p.frequency = -1.0f;
    rejects(p, "braid: `frequency` must be a finite number >= 0 and <= 1e+15 (got -1)");
    p = {};
    p.width = -0.5f;
    rejects(p, "braid: `width` must be a finite number >= 0 and <= 1e+15 (got -0.5)");
    p = {};
    p.height = -2.0f;
    rejects(p, "braid: `height` must be a finite number >= 0 and <= 1e+15 (got -2)");
    p = {};
    p.frequency = 3.0f;
    p.knot_length = 1.0f;
    rejects(p, "braid: `frequency` and `knot_length` are exclusive (got both");
    p = {};
    p.knot_length = 0.0f;
    rejects(p, "braid: `knot_length` must be a finite number > 0 (got 0)");
    p = {};
    p.samples = 1;
    rejects(p, "braid: `samples` must be >= 2");
    p = {};
    p.root_amplitude = -1.0f;
    rejects(p, "braid: `root_amplitude` must be a finite number >= 0");
    p = {};
    p.tip_amplitude = std::numeric_limits<float>::quiet_NaN();
    rejects(p, "braid: `tip_amplitude` must be a finite number >= 0");
    p = {};
    p.taper = {1.0f, -0.5f};
    rejects(p, "braid: `taper` values must be finite, >= 0 and <= 1000 (value 2 is -0.5)");
    p = {};
    p.knot_bias = 1.0f;
    rejects(p, "braid: `knot_bias` must be in (-1, 1) (got 1)");
    p = {};
    p.knot_density = {1.0f, 0.0f};
    rejects(p, "braid: `knot_density` values must be finite and > 0 (value 2 is 0)");
    p = {};
    p.clearance = -0.1f;
    rejects(p, "braid: `clearance` must be a finite number >= 0 and <= 1e+15 (got -0.1)");
    p = {};
    p.fibers = -3;
    rejects(p, "braid: `fibers` must be in [0, 1000000] (got -3)");
    p = {};
    p.fiber_radius = -1.0f;
    rejects(p, "braid: `fiber_radius` must be a finite number >= 0");
    p = {};
    p.orient = BraidOrient::Scalp;
    rejects(p, "braid: `orient` scalp needs a scalp");
    p = {};
    p.clearance = 0.1f;
    rejects(p, "braid: `clearance` needs a scalp");
    p = {};
    p.rest = true;
    rejects(p, "braid: `rest` needs a scalp");
    p = {};
    p.frequency = 1e9f;
    EXPECT_THROW(braid(guides, p), LimitExceeded);
}
