// The curl op (talk, Sec. 3.1) on straight and curved in-memory guides and an exact sphere scalp.
#include "ops/curl.h"

#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "kernel/math/polyline.h"
#include "kernel/parallel.h"
#include "ops/hair_types.h"
#include "support/ask_every_point.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <numbers>

using namespace groom;

namespace {

/// `n` straight guides along +Y, of `length`, with `points` points each, spread along X and Z.
CurveSet straight_guides(int n, float length, int points = 8)
{
    std::vector<int64_t> counts(size_t(n), points);
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    auto id = cs.add<int64_t>(Domain::Curve, attr::id);
    for (int c = 0; c < n; ++c) {
        id[size_t(c)] = 1000 + c;
        for (int i = 0; i < points; ++i) {
            P[size_t(c * points + i)] = {10.0f * float(c % 50), length * float(i) / float(points - 1), 10.0f * float(c / 50)};
        }
    }
    return cs;
}

/// Lateral offset of point p from the straight guide of curve c (the guide's x, z), in the frame
/// the op uses on a +Y line: normal +X, binormal +Y x +X = -Z.
ShapePoint lateral(const CurveSet& cs, size_t c, const float3& p)
{
    const float gx = 10.0f * float(c % 50), gz = 10.0f * float(c / 50);
    return {p.x - gx, -(p.z - gz)};
}

CurlParams exact_params(int shape)
{
    CurlParams p;
    p.dominant = shape;
    p.uniformity = 1.0f;
    p.amplitude = {0.5f, 0.5f};
    p.frequency = {0.25f, 0.25f};
    p.phase = {0.0f, 0.0f};
    p.root_ramp = 0.0f;
    return p;
}

std::string error_of(const CurlParams& p)
{
    try {
        p.validate();
    }
    catch (const InvalidParam& e) {
        return e.what();
    }
    return "(accepted)";
}

}  // namespace

// With one shape, fixed amplitude and no phase, every output point's cross-section offset divided by
// the amplitude satisfies the shape's closed form.
TEST(Curl, EachShapeSatisfiesItsClosedFormOnAStraightGuide)
{
    const CurveSet guides = straight_guides(3, 20.0f);
    for (int shape = 0; shape < curl_shape_count(); ++shape) {
        CurlParams p = exact_params(shape);
        p.shape.lame_exponent = 3.0f;
        p.shape.polygon_sides = 6;
        p.shape.ellipse_aspect = 0.4f;
        p.shape.rose_petals = 3;
        const CurveSet out = curl(guides, p);
        const auto P = out.positions();
        const auto sh = out.find<int32_t>(Domain::Point, "shape");
        ASSERT_EQ(sh.size(), P.size());
        for (size_t c = 0; c < out.num_curves(); ++c) {
            const IndexRange r = out.points_of(c);
            ASSERT_GT(r.size(), 60);  // 20 units x 0.25 cycles/unit x 16 samples
            for (int64_t i = r.begin; i < r.end; ++i) {
                ASSERT_EQ(sh[size_t(i)], shape);
                const ShapePoint q = lateral(out, c, P[size_t(i)]);
                const float x = q.x / 0.5f, y = q.y / 0.5f;
                float err = 0.0f;
                switch (shape) {
                case kLame: err = std::pow(std::fabs(x), 3.0f) + std::pow(std::fabs(y), 3.0f) - 1.0f; break;
                case kPolygon: {
                    // On one of the hexagon's edges: the support distance in the edge's normal
                    // direction equals the apothem cos(pi/6) for the nearest edge.
                    const float a = std::atan2(y, x);
                    const float edge = std::round(a / (2.0f * std::numbers::pi_v<float> / 6.0f));
                    const float na = edge * 2.0f * std::numbers::pi_v<float> / 6.0f;
                    err = x * std::cos(na) + y * std::sin(na) - std::cos(std::numbers::pi_v<float> / 6.0f);
                    break;
                }
                case kEllipse: err = x * x + (y / 0.4f) * (y / 0.4f) - 1.0f; break;
                case kCircle: err = std::hypot(x, y) - 1.0f; break;
                case kRose: err = std::hypot(x, y) - std::fabs(std::cos(3.0f * std::atan2(y, x))); break;
                }
                ASSERT_NEAR(err, 0.0f, 2e-3f) << curl_shape_name(shape) << " curve " << c << " point " << i - r.begin;
            }
        }
    }
}

// Sec. 3.1: a random pick returns the dominant shape with probability exactly U.
TEST(Curl, PickReturnsTierAWithProbabilityExactlyU)
{
    CurlParams p;
    p.hair_type = "3b";
    p.uniformity = 0.6f;
    const CurlShapeTiers t = curl_shape_tiers(p);
    EXPECT_EQ(t.dominant, kCircle);
    EXPECT_EQ(t.secondary, (std::vector<int>{kEllipse, kLame}));
    EXPECT_EQ(t.rest, (std::vector<int>{kPolygon, kRose}));
    EXPECT_DOUBLE_EQ(t.probability[kCircle], double(0.6f));
    EXPECT_NEAR(t.probability[kEllipse] + t.probability[kLame], (1.0 - 0.6f) * kCurlTierBShare, 1e-12);
    EXPECT_NEAR(t.probability[kPolygon] + t.probability[kRose], (1.0 - 0.6f) * (1.0 - kCurlTierBShare), 1e-12);
    // Exactly U: every x below U picks A, every x at or above it does not.
    EXPECT_EQ(pick_curl_shape(t, std::nextafter(double(0.6f), 0.0)), kCircle);
    EXPECT_NE(pick_curl_shape(t, double(0.6f)), kCircle);
    EXPECT_EQ(pick_curl_shape(t, 0.0), kCircle);
    EXPECT_EQ(pick_curl_shape(t, std::nextafter(1.0, 0.0)), kRose);
}

// Over thousands of cycles of real output, each tier's share matches within three standard deviations.
TEST(Curl, TierSharesOverThousandsOfCycles)
{
    CurlParams p;
    p.hair_type = "3b";
    p.uniformity = 0.6f;
    p.amplitude = {0.1f, 0.1f};
    p.frequency = {1.0f, 1.0f};
    p.samples = 4;
    p.preserve_length = false;  // so which cycles appear never depends on their shapes
    const CurveSet out = curl(straight_guides(400, 30.0f), p);
    const auto sh = out.find<int32_t>(Domain::Point, "shape");
    const auto cy = out.find<int32_t>(Domain::Point, "cycle");
    std::map<int, int64_t> count;
    int64_t cycles = 0;
    for (size_t c = 0; c < out.num_curves(); ++c) {
        const IndexRange r = out.points_of(c);
        for (int64_t i = r.begin; i < r.end; ++i) {
            if (i == r.begin || cy[size_t(i)] != cy[size_t(i - 1)]) {
                ++count[sh[size_t(i)]];
                ++cycles;
            }
        }
    }
    ASSERT_GT(cycles, 10000);
    const double n = double(cycles);
    auto check = [&](double share, double expected, const char* what) {
        const double sigma = std::sqrt(expected * (1.0 - expected) / n);
        EXPECT_NEAR(share, expected, 3.0 * sigma) << what << " over " << cycles << " cycles";
    };
    const double u = double(0.6f);
    check(double(count[kCircle]) / n, u, "tier A (circle)");
    check(double(count[kEllipse] + count[kLame]) / n, (1.0 - u) * kCurlTierBShare, "tier B (ellipse, lame)");
    check(double(count[kPolygon] + count[kRose]) / n, (1.0 - u) * (1.0 - kCurlTierBShare), "tier C (polygon, rose)");
    check(double(count[kEllipse]) / n, (1.0 - u) * kCurlTierBShare / 2.0, "ellipse");
    check(double(count[kRose]) / n, (1.0 - u) * (1.0 - kCurlTierBShare) / 2.0, "rose");
}

TEST(Curl, RestrictedShapesAndEmptyTiers)
{
    CurlParams p;
    p.hair_type = "3b";
    p.uniformity = 0.5f;
    p.shapes = {kCircle, kPolygon};  // no secondary shape allowed: tier C takes all of 1 - U
    CurlShapeTiers t = curl_shape_tiers(p);
    EXPECT_TRUE(t.secondary.empty());
    EXPECT_DOUBLE_EQ(t.probability[kPolygon], 0.5);
    EXPECT_DOUBLE_EQ(t.probability[kEllipse], 0.0);
    p.shapes = {kCircle, kEllipse, kLame};  // no tier C: tier B takes all of 1 - U
    t = curl_shape_tiers(p);
    EXPECT_TRUE(t.rest.empty());
    EXPECT_DOUBLE_EQ(t.probability[kEllipse] + t.probability[kLame], 0.5);
    const CurveSet out = curl(straight_guides(50, 20.0f), p);
    for (int32_t s : out.find<int32_t>(Domain::Point, "shape")) EXPECT_TRUE(s == kCircle || s == kEllipse || s == kLame) << s;
}

// The hair type's frequency x amplitude ratio, measured from the output geometry: cycles per unit of
// axis (from where the `cycle` attribute steps, at the points' heights) times the mean distance
// from the axis. With circles it equals the preset; with each type's own shapes it still rises
// 2a -> 4c as the table does.
TEST(Curl, MeasuredFrequencyAmplitudeRatioRisesWithHairType)
{
    auto measure = [](const CurveSet& out) {
        const auto P = out.positions();
        const auto cy = out.find<int32_t>(Domain::Point, "cycle");
        double ratio_sum = 0.0;
        int curves = 0;
        for (size_t c = 0; c < out.num_curves(); ++c) {
            const IndexRange r = out.points_of(c);
            double y_first = 0.0, y_last = 0.0, radius = 0.0;
            int k_first = -1, k_last = -1, n = 0;
            for (int64_t i = r.begin + 1; i < r.end; ++i) {
                const int k = cy[size_t(i)];
                if (k >= 1) {
                    const ShapePoint q = lateral(out, c, P[size_t(i)]);
                    radius += std::hypot(q.x, q.y);
                    ++n;
                }
                if (k != cy[size_t(i - 1)] && k >= 1) {
                    const double y = 0.5 * (P[size_t(i)].y + P[size_t(i - 1)].y);
                    if (k_first < 0) k_first = k, y_first = y;
                    k_last = k, y_last = y;
                }
            }
            if (k_last - k_first < 2 || n == 0) continue;
            const double freq = double(k_last - k_first) / (y_last - y_first);
            ratio_sum += freq * radius / n;
            ++curves;
        }
        EXPECT_GT(curves, 10);
        return ratio_sum / std::max(curves, 1);
    };
    double previous = 0.0;
    for (const HairTypePreset& preset : hair_type_presets()) {
        // Long enough for about ten cycles once the curl has shrunk the hair (pitch = radius / ratio).
        const float pitch = preset.radius_cm / preset.ratio;
        const CurveSet guides = straight_guides(40, 10.0f * pitch / (1.0f - preset.shrinkage));
        CurlParams circles;
        circles.hair_type = preset.name;
        circles.dominant = kCircle;
        circles.uniformity = 1.0f;
        const double circle_ratio = measure(curl(guides, circles));
        EXPECT_NEAR(circle_ratio, preset.ratio, 0.03 * preset.ratio) << preset.name;

        CurlParams own;
        own.hair_type = preset.name;
        const double own_ratio = measure(curl(guides, own));
        EXPECT_GT(own_ratio, previous) << preset.name << " is not curlier than the type before it";
        previous = own_ratio;
    }
}

// Cycle joins keep position and tangent continuous; without the blend window they jump, so this
// test can fail.
TEST(Curl, CycleJoinsAreContinuousInPositionAndTangent)
{
    CurlParams p;
    p.hair_type = "3c";
    p.uniformity = 0.2f;
    p.shapes = {kLame, kEllipse, kCircle, kRose};  // smooth shapes: the polygon has corners of its own
    p.amplitude = {0.3f, 0.6f};
    p.offset = {0.0f, 0.2f};
    p.frequency = {0.5f, 0.5f};
    p.samples = 128;
    const CurveSet guides = straight_guides(20, 20.0f);
    auto worst_join = [&](const CurveSet& out, double& jump, double& turn) {
        const auto P = out.positions();
        const auto cy = out.find<int32_t>(Domain::Point, "cycle");
        jump = 0.0, turn = 0.0;
        int joins = 0;
        for (size_t c = 0; c < out.num_curves(); ++c) {
            const IndexRange r = out.points_of(c);
            for (int64_t i = r.begin + 2; i + 1 < r.end; ++i) {
                if (cy[size_t(i)] == cy[size_t(i - 1)]) continue;
                ++joins;
                // Position: the segment across the join is no longer than its neighbours (ratio).
                const float3 a = P[size_t(i - 2)], b = P[size_t(i - 1)], m = P[size_t(i)], d = P[size_t(i + 1)];
                const double across = distance(b, m), beside = std::max(distance(a, b), distance(m, d));
                jump = std::max(jump, across / beside);
                // Tangent: the turning angle at both ends of that segment.
                auto angle = [](const float3& u, const float3& v) {
                    return std::acos(std::clamp(double(dot(normalize(u), normalize(v))), -1.0, 1.0));
                };
                turn = std::max({turn, angle(b - a, m - b), angle(m - b, d - m)});
            }
        }
        EXPECT_GT(joins, 50);
    };
    double jump = 0.0, turn = 0.0;
    worst_join(curl(guides, p), jump, turn);
    EXPECT_LT(jump, 1.5) << "a join jumps";
    EXPECT_LT(turn, 0.25) << "a join has a corner (radians)";
    p.blend = 0.0f;
    worst_join(curl(guides, p), jump, turn);
    EXPECT_GT(jump, 3.0) << "without blending the joins should jump (the check above would be vacuous)";
}

TEST(Curl, RootEasesInAndTheHairKeepsItsLength)
{
    CurlParams p;
    p.hair_type = "3a";
    p.root_ease = 3.0f;
    p.offset = {0.0f, 0.3f};
    const CurveSet guides = straight_guides(30, 25.0f);
    const CurveSet out = curl(guides, p);
    const auto P = out.positions();
    for (size_t c = 0; c < out.num_curves(); ++c) {
        const IndexRange r = out.points_of(c);
        const auto pts = P.subspan(size_t(r.begin), size_t(r.size()));
        EXPECT_NEAR(polyline_length(pts), 25.0f, 0.01f * 25.0f) << "curve " << c;
        // The root stays put and the first root_ease units are straight.
        EXPECT_LT(distance(pts[0], guides.positions()[size_t(c) * 8]), 1e-4f);
        int straight = 0;
        for (const float3& q : pts) {
            if (q.y < 3.0f - 1e-3f) {
                const ShapePoint l = lateral(out, c, q);
                EXPECT_LT(std::hypot(l.x, l.y), 1e-4f) << "curve " << c << " y " << q.y;
                ++straight;
            }
        }
        EXPECT_GT(straight, 2);
        // Curling shrinks the hair along its guide (the curl index): the tip ends below 25.
        EXPECT_LT(pts.back().y, 25.0f * 0.99f);
    }
    // Without length preservation the whole guide is curled and the hair grows longer.
    p.preserve_length = false;
    const CurveSet whole = curl(guides, p);
    const IndexRange r = whole.points_of(0);
    EXPECT_NEAR(whole.positions()[size_t(r.end - 1)].y, 25.0f, 1e-3f);
    EXPECT_GT(polyline_length(whole.positions().subspan(size_t(r.begin), size_t(r.size()))), 25.0f * 1.05f);
}

// Length is kept for every type, including tight coils whose curled hair covers a quarter of its
// guide, and with shapes of sharp curvature (the star-like Lame curve, the rose).
TEST(Curl, KeepsTheHairLengthForEveryHairType)
{
    CurveSet guides = straight_guides(10, 30.0f, 6);
    auto P = guides.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i].z += 0.5f * std::sin(0.2f * P[i].y);  // gently bent
    for (const HairTypePreset& preset : hair_type_presets()) {
        CurlParams p;
        p.hair_type = preset.name;
        p.uniformity = 0.2f;
        p.shape.lame_exponent = 0.7f;
        const CurveSet out = curl(guides, p);
        for (size_t c = 0; c < out.num_curves(); ++c) {
            const IndexRange a = guides.points_of(c), b = out.points_of(c);
            const float want = polyline_length(P.subspan(size_t(a.begin), size_t(a.size())));
            const float got = polyline_length(out.positions().subspan(size_t(b.begin), size_t(b.size())));
            EXPECT_NEAR(got, want, 0.005f * want) << preset.name << " curve " << c;
        }
    }
}

// Frames are rotation-minimising: on a strongly bent guide, circle curls stay at exactly the
// amplitude from the centreline (no frame collapse) and the cross-section never flips.
TEST(Curl, CirclesStayAtTheAmplitudeOnABentGuide)
{
    const int n = 64;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{n});
    auto P = cs.positions_for_write();
    for (int i = 0; i < n; ++i) {
        const float a = 1.5f * std::numbers::pi_v<float> * float(i) / float(n - 1);
        P[size_t(i)] = {10.0f * std::cos(a), 10.0f * std::sin(a), 2.0f * a};  // a helix-like guide
    }
    CurlParams p = exact_params(kCircle);
    p.frequency = {1.0f, 1.0f};
    p.amplitude = {0.4f, 0.4f};
    p.samples = 32;
    p.preserve_length = false;
    const CurveSet out = curl(cs, p);
    const auto Q = out.positions();
    // The centreline is a Catmull-Rom through the guide: measure to the densely sampled guide.
    const auto dense = resample_by_count(P, 20000);
    for (size_t i = 0; i < Q.size(); i += 7) {
        float best = INFINITY;
        for (const float3& g : dense) best = std::min(best, distance(g, Q[i]));
        ASSERT_NEAR(best, 0.4f, 0.02f) << "point " << i;
    }
}

TEST(Curl, NoCurledPointInsideTheScalp)
{
    // Guides lying 0.05 above a unit sphere along its surface direction: curls of radius 0.3 dip in.
    const AnalyticSphere sphere({0.0f, 0.0f, 0.0f}, 1.0f);
    const int curves = 40, n = 16;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(curves, n));
    auto P = cs.positions_for_write();
    for (int c = 0; c < curves; ++c) {
        const float az = 2.0f * std::numbers::pi_v<float> * float(c) / curves;
        for (int i = 0; i < n; ++i) {
            const float polar = 0.1f + 1.2f * float(i) / float(n - 1);  // over the top of the sphere
            P[size_t(c * n + i)] = float3(std::sin(polar) * std::cos(az), std::cos(polar), std::sin(polar) * std::sin(az)) * 1.05f;
        }
    }
    CurlParams p;
    p.amplitude = {0.3f, 0.3f};
    p.frequency = {2.0f, 2.0f};
    p.root_ramp = 0.0f;
    int inside_without = 0;
    const CurveSet without = curl(cs, p);  // named: a range-for over a temporary's span reads freed memory
    for (const float3& q : without.positions()) inside_without += sphere.inside(q);
    ASSERT_GT(inside_without, 100) << "the setup must push points inside, or the check below is vacuous";
    const CurveSet out = curl(cs, p, &sphere);
    int inside = 0;
    for (const float3& q : out.positions()) inside += sphere.inside(q);
    EXPECT_EQ(inside, 0);
}

TEST(CurlReal, OnSintelTheVoxelsShortcutChangesNoBit)
{
    GROOM_REQUIRE_SHARED(head, "sintel_tressfx_opengl/sintel.obj");
    GROOM_REQUIRE_SHARED(guides_path, "sintel_tressfx_opengl/sintel_guides.obj");
    // Sintel's own guides curled tightly along her open head (rims, seams), many points dipping
    // into it: the same bits whether the voxels' bytes say "clear" (fields/clear_cells.h) or every
    // point is asked in full.
    const ScalpField field = build_scalp(read_mesh(head));
    const CurveSet guides = read_curves(guides_path);
    CurlParams params;
    params.amplitude = {0.6f, 0.9f};
    params.frequency = {1.0f, 1.5f};
    params.labels = false;
    const CurveSet loose = curl(guides, params);
    int inside = 0;
    for (const float3& q : loose.positions()) inside += field.inside(q);
    ASSERT_GT(inside, 200) << "the curls must dip into the head, or the comparison below is vacuous";
    const CurveSet quick = curl(guides, params, &field);
    const test::AskEveryPoint every(field);
    const CurveSet full = curl(guides, params, &every);
    const auto pq = quick.positions(), pf = full.positions();
    ASSERT_EQ(pq.size(), pf.size());
    EXPECT_EQ(std::memcmp(pq.data(), pf.data(), pq.size() * sizeof(float3)), 0);
}

TEST(Curl, SameResultForOneAndTwoThreadsAndIndependentOfCurveOrder)
{
    CurveSet guides = straight_guides(300, 15.0f, 12);
    auto P = guides.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i].x += 0.3f * std::sin(0.37f * float(i));  // bent guides
    CurlParams p;
    p.hair_type = "4a";
    p.uniformity = 0.4f;
    p.offset = {0.0f, 0.05f};
    p.seed = 7;
    CurveSet one, two;
    {
        ThreadLimit limit(1);
        one = curl(guides, p);
    }
    {
        ThreadLimit limit(2);
        two = curl(guides, p);
    }
    ASSERT_EQ(one.num_points(), two.num_points());
    EXPECT_EQ(std::memcmp(one.positions().data(), two.positions().data(), one.num_points() * sizeof(float3)), 0);
    EXPECT_TRUE(std::ranges::equal(one.find<int32_t>(Domain::Point, "shape"), two.find<int32_t>(Domain::Point, "shape")));
    EXPECT_TRUE(std::ranges::equal(one.find<int32_t>(Domain::Point, "cycle"), two.find<int32_t>(Domain::Point, "cycle")));

    // Curve 5 alone (same id) curls exactly as it did among the others.
    const IndexRange r = guides.points_of(5);
    CurveSet single = CurveSet::from_counts(std::vector<int64_t>{r.size()});
    std::copy(P.begin() + r.begin, P.begin() + r.end, single.positions_for_write().begin());
    single.add<int64_t>(Domain::Curve, attr::id)[0] = guides.find<int64_t>(Domain::Curve, attr::id)[5];
    const CurveSet alone = curl(single, p);
    const IndexRange o = one.points_of(5);
    ASSERT_EQ(alone.num_points(), size_t(o.size()));
    EXPECT_EQ(std::memcmp(alone.positions().data(), one.positions().data() + o.begin, alone.num_points() * sizeof(float3)), 0);
    // Another seed gives another groom.
    p.seed = 8;
    const CurveSet other = curl(guides, p);
    EXPECT_FALSE(other.num_points() == one.num_points() &&
                 std::memcmp(other.positions().data(), one.positions().data(), one.num_points() * sizeof(float3)) == 0);
}

// Written a block at a time (groom curl into .hair never holds its whole output), every curve is
// curled exactly as curl() curls it: the blocks, laid end to end, are curl()'s output column for
// column, bit for bit, however the blocks are cut, with a scalp or without.
TEST(Curl, BlocksEndToEndAreTheWholeCurl)
{
    CurveSet guides = straight_guides(120, 6.0f, 9);
    auto P = guides.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i].x += 0.2f * std::sin(0.41f * float(i));
    auto w = guides.add<float>(Domain::Point, attr::width);
    auto cd = guides.add<float3>(Domain::Point, "Cd");
    auto clump = guides.add<int32_t>(Domain::Curve, "clump");
    for (size_t i = 0; i < w.size(); ++i) w[i] = 0.01f + 0.001f * float(i % 9), cd[i] = {float(i % 9), 0.5f, 1.0f};
    for (size_t c = 0; c < clump.size(); ++c) clump[c] = int32_t(3 * c);
    CurlParams p;
    p.hair_type = "3c";
    p.seed = 11;
    // Curves over the plane y = 0.5 above their roots: some curled points dip below it.
    const AnalyticPlane floor({0.0f, 0.5f, 0.0f}, {0.0f, 1.0f, 0.0f});
    for (const Surface* scalp : {static_cast<const Surface*>(nullptr), static_cast<const Surface*>(&floor)}) {
        const CurveSet whole = curl(guides, p, scalp);
        for (const int64_t block_points : {int64_t(1), int64_t(500), int64_t(1) << 40}) {
            std::vector<int64_t> announced;
            std::vector<CurveSet> blocks;
            curl_blocks(
                guides, p, scalp, nullptr, block_points, [&](std::span<const int64_t> counts) { announced.assign(counts.begin(), counts.end()); },
                [&](const CurveSet& b) { blocks.push_back(b); });
            SCOPED_TRACE("block_points " + std::to_string(block_points) + (scalp ? ", over a plane" : ""));
            ASSERT_EQ(announced.size(), whole.num_curves());
            if (block_points != 500) EXPECT_EQ(blocks.size(), block_points == 1 ? whole.num_curves() : 1u);
            size_t curve = 0, point = 0;
            for (const CurveSet& b : blocks) {
                EXPECT_EQ(b.detail_string("hair_type"), "3c");
                for (size_t c = 0; c < b.num_curves(); ++c, ++curve) {
                    ASSERT_EQ(b.points_in(c), whole.points_in(curve));
                    EXPECT_EQ(announced[curve], whole.points_in(curve));
                    EXPECT_EQ(b.find<int32_t>(Domain::Curve, "clump")[c], whole.find<int32_t>(Domain::Curve, "clump")[curve]);
                    EXPECT_EQ(b.find<int64_t>(Domain::Curve, attr::id)[c], whole.find<int64_t>(Domain::Curve, attr::id)[curve]);
                }
                const size_t n = b.num_points();
                EXPECT_EQ(std::memcmp(b.positions().data(), whole.positions().data() + point, n * sizeof(float3)), 0);
                EXPECT_EQ(std::memcmp(b.find<float>(Domain::Point, attr::width).data(), whole.find<float>(Domain::Point, attr::width).data() + point,
                                      n * sizeof(float)), 0);
                EXPECT_EQ(std::memcmp(b.find<float3>(Domain::Point, "Cd").data(), whole.find<float3>(Domain::Point, "Cd").data() + point,
                                      n * sizeof(float3)), 0);
                EXPECT_TRUE(std::ranges::equal(b.find<int32_t>(Domain::Point, "shape"),
                                               whole.find<int32_t>(Domain::Point, "shape").subspan(point, n)));
                EXPECT_TRUE(std::ranges::equal(b.find<int32_t>(Domain::Point, "cycle"),
                                               whole.find<int32_t>(Domain::Point, "cycle").subspan(point, n)));
                point += n;
            }
            EXPECT_EQ(curve, whole.num_curves());
            EXPECT_EQ(point, whole.num_points());
            if (block_points == 500) EXPECT_GT(blocks.size(), 3u);
        }
        if (scalp) {
            int below = 0;
            for (const float3& q : whole.positions()) below += floor.inside(q);
            EXPECT_EQ(below, 0);
        }
    }
}

TEST(Curl, CarriesAttributesThrough)
{
    CurveSet guides = straight_guides(4, 10.0f, 5);
    auto w = guides.add<float>(Domain::Point, attr::width);
    auto cd = guides.add<float3>(Domain::Point, "Cd");
    auto clump = guides.add<int32_t>(Domain::Curve, "clump");
    for (size_t i = 0; i < w.size(); ++i) {
        w[i] = 0.1f - 0.02f * float(i % 5);  // tapers linearly from 0.1 at the root to 0.02 at the tip
        cd[i] = {float(i % 5), 0.0f, 1.0f};
    }
    for (size_t c = 0; c < 4; ++c) clump[c] = int32_t(10 * c);
    guides.set_detail_string("source", "unit test");
    CurlParams p;
    p.hair_type = "4b";
    p.preserve_length = false;  // so each output point's centreline height is its input height
    const CurveSet out = curl(guides, p);
    EXPECT_NO_THROW(out.validate());
    EXPECT_EQ(out.detail_string("hair_type"), "4b");
    EXPECT_EQ(out.detail_string("source"), "unit test");
    const auto oc = out.find<int32_t>(Domain::Curve, "clump");
    ASSERT_EQ(oc.size(), 4u);
    for (size_t c = 0; c < 4; ++c) EXPECT_EQ(oc[c], int32_t(10 * c));
    EXPECT_TRUE(std::ranges::equal(out.find<int64_t>(Domain::Curve, attr::id), guides.find<int64_t>(Domain::Curve, attr::id)));
    const auto ow = out.find<float>(Domain::Point, attr::width);
    const auto ocd = out.find<float3>(Domain::Point, "Cd");
    ASSERT_EQ(ow.size(), out.num_points());
    ASSERT_EQ(ocd.size(), out.num_points());
    for (size_t c = 0; c < 4; ++c) {
        const IndexRange r = out.points_of(c);
        EXPECT_GT(r.size(), 5);
        for (int64_t i = r.begin; i < r.end; ++i) {
            const float f = float(i - r.begin) / float(r.size() - 1);  // arc fraction along the guide
            EXPECT_NEAR(ow[size_t(i)], 0.1f - 0.08f * f, 1e-4f);
            EXPECT_NEAR(ocd[size_t(i)].x, std::round(4.0f * f), 0.5f + 1e-4f);  // nearest input point's value
        }
    }
}

TEST(Curl, DegenerateCurvesPassThrough)
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{1, 3, 0});
    auto P = cs.positions_for_write();
    P[0] = {1, 2, 3};
    P[1] = P[2] = P[3] = {4, 5, 6};  // zero length
    const CurveSet out = curl(cs, CurlParams{});
    ASSERT_EQ(out.num_points(), 4u);
    EXPECT_EQ(out.positions()[0], float3(1, 2, 3));
    EXPECT_EQ(out.positions()[3], float3(4, 5, 6));
    EXPECT_EQ(out.points_in(2), 0);
}

TEST(Curl, RejectsEveryInvalidOption)
{
    auto expect = [](CurlParams p, const std::string& option) {
        const std::string e = error_of(p);
        EXPECT_NE(e.find("curl: " + option), std::string::npos) << option << ": " << e;
    };
    EXPECT_EQ(error_of(CurlParams{}), "(accepted)");
    CurlParams p;
    p.hair_type = "5a";
    expect(p, "`type`");
    EXPECT_NE(error_of(p).find("2a|2b|2c|3a|3b|3c|4a|4b|4c"), std::string::npos);
    p = {};
    p.uniformity = 1.5f;
    expect(p, "`uniformity`");
    p.uniformity = -0.1f;
    expect(p, "`uniformity`");
    p.uniformity = NAN;
    expect(p, "`uniformity`");
    p = {};
    p.dominant = 5;
    expect(p, "`dominant`");
    p = {};
    p.shapes = {kCircle, 9};
    expect(p, "`shapes`");
    p.shapes = {kCircle, kCircle};
    expect(p, "`shapes`");
    p = {};
    p.shapes = {kEllipse, kRose};  // type 3a's dominant (circle) is not allowed
    expect(p, "`dominant`");
    p = {};
    p.shapes = {kCircle};
    p.uniformity = 0.5f;  // 1 - U must go to other shapes, but there are none
    expect(p, "`uniformity`");
    p.uniformity = 1.0f;
    EXPECT_EQ(error_of(p), "(accepted)");
    p = {};
    p.amplitude = {0.5f, 0.2f};
    expect(p, "`amplitude`");
    p.amplitude = {-0.1f, 0.2f};
    expect(p, "`amplitude`");
    p.amplitude = {0.1f, INFINITY};
    expect(p, "`amplitude`");
    p = {};
    p.frequency = {0.0f, 1.0f};
    expect(p, "`frequency`");
    p.frequency = {2.0f, 1.0f};
    expect(p, "`frequency`");
    p = {};
    p.phase = {1.0f, 0.0f};
    expect(p, "`phase`");
    p = {};
    p.offset = {-1.0f, 0.0f};
    expect(p, "`offset`");
    p = {};
    p.units_per_cm = 0.0f;
    expect(p, "`units_per_cm`");
    p = {};
    p.root_ease = -1.0f;
    expect(p, "`root_ease`");
    p = {};
    p.root_ramp = NAN;
    expect(p, "`root_ramp`");
    p = {};
    p.samples = 3;
    expect(p, "`samples`");
    p = {};
    p.blend = 0.5f;
    expect(p, "`blend`");
    p = {};
    p.shape.polygon_sides = 2;
    expect(p, "`polygon_sides`");
    // The op validates too.
    p = {};
    p.samples = 1000;
    EXPECT_THROW(curl(straight_guides(1, 1.0f), p), InvalidParam);
}

TEST(Curl, RefusesOutputsBeyondTheLimit)
{
    CurlParams p;
    p.frequency = {1e6f, 1e6f};
    p.samples = 256;
    EXPECT_THROW(curl(straight_guides(10, 100.0f), p), LimitExceeded);
}
