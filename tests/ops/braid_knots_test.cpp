// Tests for ops/braid_knots: where braid puts its knots (frequency or knot length, the bias and
// density remap alpha(t)) and the knot centres `groom partition --centroids knots` shares, against
// closed forms.
#include "ops/braid.h"

#include <gtest/gtest.h>

#include <cstddef>

using namespace groom;

// Knot placement shared with `groom partition --centroids knots`: F alpha(t_k) = k + 1/2.
TEST(Braid, KnotParametersFollowFrequencyAndRemap)
{
    BraidParams p;
    p.frequency = 4.0f;
    const auto t = braid_knot_parameters(p, 12.0);
    ASSERT_EQ(t.size(), 4u);
    for (size_t k = 0; k < 4; ++k) EXPECT_NEAR(t[k], (k + 0.5) / 4.0, 1e-7);

    // Knot length: F = length / L, knots L apart in arc length.
    BraidParams q;
    q.knot_length = 1.5f;
    const auto tl = braid_knot_parameters(q, 12.0);
    ASSERT_EQ(tl.size(), 8u);
    for (size_t k = 0; k + 1 < tl.size(); ++k) EXPECT_NEAR((tl[k + 1] - tl[k]) * 12.0, 1.5, 1e-5);
    EXPECT_NEAR(braid_frequency(q, 12.0), 8.0, 1e-12);
    // Only knots whose centre lies on the guide: F = 2.4 has 2.
    p.frequency = 2.4f;
    EXPECT_EQ(braid_knot_parameters(p, 1.0).size(), 2u);

    // Bias > 0 packs knots toward the tip; every knot centre satisfies F alpha(t_k) = k + 1/2.
    p.frequency = 10.0f;
    p.knot_bias = 0.5f;
    const KnotRemap remap(p);
    const auto tb = braid_knot_parameters(p, 1.0);
    ASSERT_EQ(tb.size(), 10u);
    for (size_t k = 0; k < tb.size(); ++k) EXPECT_NEAR(10.0 * remap.alpha(tb[k]), k + 0.5, 1e-4);
    EXPECT_GT(tb[1] - tb[0], tb[9] - tb[8]);
}

// alpha(t): identity by default; Schlick bias slopes g/(1-g) at the root, (1-g)/g at the tip; the
// density spline integrates to the closed form.
TEST(Braid, KnotRemapMatchesClosedForms)
{
    BraidParams p;
    EXPECT_TRUE(KnotRemap(p).identity());
    EXPECT_EQ(KnotRemap(p).alpha(0.3), 0.3);

    p.knot_bias = 0.5f;  // g = 0.25
    const KnotRemap bias(p);
    EXPECT_NEAR(bias.alpha(0.0), 0.0, 1e-12);
    EXPECT_NEAR(bias.alpha(1.0), 1.0, 1e-12);
    const double h = 1e-6;
    EXPECT_NEAR(bias.alpha(h) / h, 1.0 / 3.0, 1e-4);
    EXPECT_NEAR((1.0 - bias.alpha(1.0 - h)) / h, 3.0, 1e-4);
    EXPECT_NEAR(bias.max_slope(), 3.0, 1e-9);
    for (double t = 0.0; t <= 1.0; t += 0.05) EXPECT_NEAR(bias.inverse(bias.alpha(t)), t, 1e-9);

    // Density 1 + 2t (two values: the clamped spline is linear): alpha = (t + t^2) / 2.
    BraidParams d;
    d.knot_density = {1.0f, 3.0f};
    const KnotRemap dens(d);
    for (double t = 0.0; t <= 1.0; t += 0.05) {
        EXPECT_NEAR(dens.alpha(t), (t + t * t) / 2.0, 1e-6) << t;
        EXPECT_NEAR(dens.inverse(dens.alpha(t)), t, 1e-6) << t;
    }
    EXPECT_NEAR(dens.max_slope(), 1.5, 1e-3);
}
