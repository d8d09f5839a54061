// Tests for ops/populate: fibers in a disc around each curve, checked on straight lines and circles
// against closed forms, the area-uniform disc statistically, ids, carry-through, rejection, determinism.
#include "ops/populate.h"

#include "kernel/error.h"
#include "kernel/math/polyline.h"
#include "kernel/parallel.h"
#include "make_curves.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <set>

using namespace groom;
using groom::test::make_curves;

namespace {

std::vector<float3> line_z(float x, float y, int n, float len)
{
    std::vector<float3> pts;
    for (int k = 0; k < n; ++k) pts.emplace_back(x, y, len * k / (n - 1));
    return pts;
}

}  // namespace

// Around a straight curve every fiber is a parallel line at a fixed offset inside the disc.
TEST(Populate, FibersAreParallelInsideTheDiscOfAStraightCurve)
{
    CurveSet src = make_curves({line_z(1, 2, 11, 5.0f), line_z(-3, 0, 4, 2.0f)});
    auto id = src.add<int64_t>(Domain::Curve, attr::id);
    id[0] = 5;
    id[1] = 6;
    PopulateParams p;
    p.count = 50;
    p.radius = 0.25f;
    p.seed = 9;
    const CurveSet out = populate(src, p);
    out.validate();
    ASSERT_EQ(out.num_curves(), 100u);
    const auto fiber = out.find<int32_t>(Domain::Curve, "fiber");
    const auto oid = out.find<int64_t>(Domain::Curve, attr::id);
    const auto W = out.find<float>(Domain::Point, attr::width);
    ASSERT_FALSE(fiber.empty());
    ASSERT_FALSE(oid.empty());
    ASSERT_FALSE(W.empty());
    std::set<std::pair<float, float>> offsets;
    for (size_t c = 0; c < 100; ++c) {
        const size_t s = c / 50;
        EXPECT_EQ(fiber[c], int32_t(c % 50));
        EXPECT_EQ(oid[c], (s == 0 ? 5 : 6) * 50 + int64_t(c % 50));
        ASSERT_EQ(out.points_in(c), s == 0 ? 11 : 4);
        const float3 centre(s == 0 ? 1.0f : -3.0f, s == 0 ? 2.0f : 0.0f, 0.0f);
        const float3 first = out.positions()[out.points_of(c).begin] - centre;
        EXPECT_LE(std::hypot(first.x, first.y), 0.25f + 1e-6f);
        for (int64_t j = 0; j < out.points_in(c); ++j) {
            const int64_t q = out.points_of(c).begin + j;
            const float3 off = out.positions()[q] - centre;
            EXPECT_NEAR(off.x, first.x, 1e-6f);
            EXPECT_NEAR(off.y, first.y, 1e-6f);
            EXPECT_NEAR(off.z, src.positions()[src.points_of(s).begin + j].z, 1e-6f);
            EXPECT_NEAR(W[q], 2.0f * 0.25f / std::sqrt(50.0f), 1e-7f);  // automatic: fibers cover the disc
        }
        if (s == 0) offsets.insert({first.x, first.y});
    }
    EXPECT_EQ(offsets.size(), 50u);  // every fiber its own offset
}

// The disc is filled area-uniformly: half the fibers inside radius r / sqrt(2), a quarter per quadrant.
TEST(Populate, DiscIsAreaUniform)
{
    const CurveSet src = make_curves({line_z(0, 0, 2, 1.0f)});
    PopulateParams p;
    p.count = 8000;
    p.radius = 2.0f;
    const CurveSet out = populate(src, p);
    int inner = 0, quadrant[4] = {0, 0, 0, 0};
    for (size_t c = 0; c < out.num_curves(); ++c) {
        const float3 q = out.positions()[out.points_of(c).begin];
        const float r = std::hypot(q.x, q.y);
        ASSERT_LE(r, 2.0f + 1e-6f);
        if (r < 2.0f / std::sqrt(2.0f)) ++inner;
        ++quadrant[(q.x >= 0 ? 0 : 1) + (q.y >= 0 ? 0 : 2)];
    }
    // Binomial standard deviations: sqrt(8000 / 4) = 45 inner, sqrt(8000 * 3 / 16) = 39 per quadrant; 5 sigma.
    EXPECT_NEAR(inner, 4000, 225);
    for (const int n : quadrant) EXPECT_NEAR(n, 2000, 195);
}

// Around a circle the offsets ride the rotation-minimising frame: each fiber keeps its distance to the
// centreline and stays in the plane normal to the tangent.
TEST(Populate, OffsetsStayInTheNormalPlaneOfACurvedCurve)
{
    std::vector<float3> arc;
    for (int k = 0; k <= 200; ++k) {
        const double th = 1.5 * std::numbers::pi * k / 200.0;
        arc.emplace_back(float(3.0 * std::cos(th)), float(3.0 * std::sin(th)), 0.0f);
    }
    const CurveSet src = make_curves({arc});
    PopulateParams p;
    p.count = 12;
    p.radius = 0.3f;
    const CurveSet out = populate(src, p);
    const auto T = polyline_tangents(arc);
    for (size_t c = 0; c < out.num_curves(); ++c) {
        const float d0 = distance(out.positions()[out.points_of(c).begin], arc[0]);
        EXPECT_LE(d0, 0.3f + 1e-5f);
        for (int j = 0; j <= 200; ++j) {
            const float3 off = out.positions()[out.points_of(c).begin + j] - arc[j];
            EXPECT_NEAR(length(off), d0, 1e-5f) << c << " " << j;
            EXPECT_NEAR(dot(off, T[j]), 0.0f, 1e-5f) << c << " " << j;
        }
    }
}

// Radius 0 fills each curve within its own width; radius_scale scales the disc per point.
TEST(Populate, RadiusFromWidthAndPerPointScale)
{
    CurveSet src = make_curves({line_z(0, 0, 5, 4.0f)});
    auto w = src.add<float>(Domain::Point, attr::width);
    auto scale = src.add<float>(Domain::Point, "taper");
    for (int j = 0; j < 5; ++j) {
        w[j] = 1.0f - 0.2f * j;
        scale[j] = 1.0f + j;
    }
    PopulateParams p;
    p.count = 30;
    const CurveSet from_width = populate(src, p);
    p.radius = 0.1f;
    p.radius_scale = "taper";
    p.width = 0.01f;
    const CurveSet scaled = populate(src, p);
    const auto W = scaled.find<float>(Domain::Point, attr::width);
    for (size_t c = 0; c < 30; ++c) {
        // Same seed and id: the same unit-disc offset, so radii compare exactly in ratio.
        const float3 a0 = from_width.positions()[from_width.points_of(c).begin];
        const float3 b0 = scaled.positions()[scaled.points_of(c).begin];
        for (int j = 0; j < 5; ++j) {
            const float3 a = from_width.positions()[from_width.points_of(c).begin + j];
            const float3 b = scaled.positions()[scaled.points_of(c).begin + j];
            EXPECT_NEAR(std::hypot(a.x, a.y), std::hypot(a0.x, a0.y) * (1.0f - 0.2f * j), 1e-6f);
            EXPECT_NEAR(std::hypot(b.x, b.y), std::hypot(b0.x, b0.y) * (1.0f + j), 1e-6f);
            EXPECT_EQ(W[scaled.points_of(c).begin + j], 0.01f);
        }
    }
}

TEST(Populate, RejectsInvalidOptions)
{
    const CurveSet src = make_curves({line_z(0, 0, 3, 1.0f)});
    const auto message = [&](PopulateParams p) {
        try {
            populate(src, p);
        }
        catch (const InvalidParam& e) {
            return std::string(e.what());
        }
        return std::string("(no InvalidParam thrown)");
    };
    PopulateParams p;
    p.count = 0;
    p.radius = 1.0f;
    EXPECT_EQ(message(p), "populate: `count` must be in [1, 1000000] (got 0)");
    p.count = 3;
    p.radius = -1.0f;
    EXPECT_EQ(message(p), "populate: `radius` must be a finite number >= 0 (got -1)");
    p.radius = 1.0f;
    p.width = std::nanf("");
    EXPECT_NE(message(p).find("populate: `width` must be a finite number >= 0"), std::string::npos);
    p.width = 0.0f;
    p.radius = 0.0f;
    EXPECT_NE(message(p).find("lacks (give `radius` r > 0)"), std::string::npos);
    p.radius = 1.0f;
    p.radius_scale = "nope";
    EXPECT_NE(message(p).find("'nope' is not a point float attribute"), std::string::npos);
}

// Fibers depend on (seed, curve id) only: the same for 1 and 2 threads, and unchanged when other
// curves are removed or the order changes.
TEST(Populate, DeterministicAcrossThreadsAndCurveOrder)
{
    std::vector<std::vector<float3>> lines;
    for (int c = 0; c < 300; ++c) lines.push_back(line_z(float(c), 0, 6, 1.0f + c % 3));
    CurveSet src = make_curves(lines);
    auto id = src.add<int64_t>(Domain::Curve, attr::id);
    for (int c = 0; c < 300; ++c) id[c] = 1000 + c;
    PopulateParams p;
    p.count = 7;
    p.radius = 0.2f;
    p.seed = 77;
    const auto run = [&](const CurveSet& cs, int threads) {
        ThreadLimit limit(threads);
        return populate(cs, p);
    };
    const CurveSet a = run(src, 1), b = run(src, 2);
    ASSERT_EQ(a.num_points(), b.num_points());
    EXPECT_EQ(std::memcmp(a.positions().data(), b.positions().data(), a.num_points() * sizeof(float3)), 0);

    // Only curve 123, on its own: its fibers are the same as in the full run.
    CurveSet one = make_curves({lines[123]});
    one.add<int64_t>(Domain::Curve, attr::id)[0] = 1123;
    const CurveSet c = run(one, 2);
    for (int f = 0; f < 7; ++f) {
        for (int j = 0; j < 6; ++j) {
            EXPECT_EQ(c.positions()[c.points_of(f).begin + j], a.positions()[a.points_of(123 * 7 + f).begin + j]);
        }
    }
    // A different seed moves them.
    p.seed = 78;
    const CurveSet d = run(src, 2);
    EXPECT_NE(std::memcmp(a.positions().data(), d.positions().data(), a.num_points() * sizeof(float3)), 0);
}

TEST(Populate, CarriesAttributes)
{
    CurveSet src = make_curves({line_z(0, 0, 3, 1.0f), line_z(1, 0, 2, 1.0f)});
    auto guide = src.add<int32_t>(Domain::Curve, "guide");
    guide[0] = 3;
    guide[1] = 8;
    auto temp = src.add<float>(Domain::Point, "temp");
    for (size_t q = 0; q < temp.size(); ++q) temp[q] = float(q);
    src.set_detail_string("note", "x");
    PopulateParams p;
    p.count = 2;
    p.radius = 0.1f;
    const CurveSet out = populate(src, p);
    const auto og = out.find<int32_t>(Domain::Curve, "guide");
    const auto ot = out.find<float>(Domain::Point, "temp");
    ASSERT_FALSE(og.empty());
    ASSERT_FALSE(ot.empty());
    EXPECT_EQ(std::vector<int32_t>(og.begin(), og.end()), (std::vector<int32_t>{3, 3, 8, 8}));
    EXPECT_EQ(std::vector<float>(ot.begin(), ot.end()), (std::vector<float>{0, 1, 2, 0, 1, 2, 3, 4, 3, 4}));
    EXPECT_EQ(out.detail_string("note"), "x");
}
