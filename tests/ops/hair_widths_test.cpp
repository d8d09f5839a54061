// hair widths: the root-to-tip taper every op that makes hairs writes, against its closed form.
#include "kernel/error.h"
#include "ops/hair_widths.h"
#include "tests/ops/make_curves.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace groom;
using groom::test::make_curves;

namespace {

/// Points of an uneven polyline: segment k has length 1 + k (so arc length is not the point index).
std::vector<float3> uneven(int n, float3 at)
{
    std::vector<float3> pts;
    float s = 0.0f;
    for (int k = 0; k < n; ++k) {
        pts.push_back(at + float3(s, 0.1f * float(k * k), 0));
        s += 1.0f + float(k);
    }
    return pts;
}

/// Checks every curve of `cs` against w = (1 - f) root + f tip, f its fraction of arc length.
void expect_linear_taper(const CurveSet& cs, float root, float tip)
{
    const auto W = cs.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(W.size(), cs.num_points());
    const auto P = cs.positions();
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const IndexRange r = cs.points_of(c);
        EXPECT_EQ(W[r.begin], root) << "curve " << c;
        if (r.size() > 1) EXPECT_EQ(W[r.end - 1], tip) << "curve " << c;
        double total = 0.0;
        for (int64_t i = r.begin + 1; i < r.end; ++i) total += length(P[i] - P[i - 1]);
        double s = 0.0;
        for (int64_t i = r.begin; i < r.end; ++i) {
            if (i > r.begin) s += length(P[i] - P[i - 1]);
            const double f = total > 0 ? s / total : 0.0;
            EXPECT_NEAR(W[i], (1 - f) * root + f * tip, 1e-6 * std::max(root, tip)) << "curve " << c << " point " << i - r.begin;
            // Monotone toward the tip width, to float rounding.
            if (i > r.begin) {
                if (root >= tip) EXPECT_LE(W[i], W[i - 1]);
                else EXPECT_GE(W[i], W[i - 1]);
            }
        }
    }
}

}  // namespace

TEST(HairWidths, TaperIsLinearInArcLengthRootAndTipExact)
{
    CurveSet cs = make_curves({uneven(7, {0, 0, 0}), uneven(40, {0, 5, 0}), uneven(2, {0, 9, 0})});
    taper_widths(cs, 0.008f, 0.004f);
    expect_linear_taper(cs, 0.008f, 0.004f);
    taper_widths(cs, 0.003f, 0.011f);  // a flare is monotone too
    expect_linear_taper(cs, 0.003f, 0.011f);
    taper_widths(cs, 0.01f, 0.0f);  // to a point
    expect_linear_taper(cs, 0.01f, 0.0f);
}

TEST(HairWidths, DegenerateCurvesGetRootWidthOrTheIndexFraction)
{
    CurveSet cs = make_curves({{float3(1, 1, 1)}, {float3(2, 2, 2), float3(2, 2, 2), float3(2, 2, 2)}});
    taper_widths(cs, 0.5f, 0.1f);
    const auto W = cs.find<float>(Domain::Point, attr::width);
    EXPECT_EQ(W[0], 0.5f);  // one point: the root
    EXPECT_EQ(W[1], 0.5f);  // no length: by point index
    EXPECT_FLOAT_EQ(W[2], 0.3f);
    EXPECT_EQ(W[3], 0.1f);
}

TEST(HairWidths, ApplyKeepsCarriedWidthsUnlessAsked)
{
    CurveSet cs = make_curves({uneven(5, {0, 0, 0})});
    // No width: the human-hair defaults, scaled by units per cm.
    apply_hair_widths(cs, {});
    expect_linear_taper(cs, kDefaultRootWidthCm, kDefaultTipWidthCm);
    cs.attributes(Domain::Point).remove(attr::width);
    apply_hair_widths(cs, {}, 10.0f);  // millimetres
    expect_linear_taper(cs, kDefaultRootWidthCm * 10.0f, kDefaultTipWidthCm * 10.0f);

    // Carried widths stay, bit for bit.
    auto W = cs.find_for_write<float>(Domain::Point, attr::width);
    const std::vector<float> mine{0.7f, 0.1f, 0.9f, 0.2f, 0.5f};
    std::copy(mine.begin(), mine.end(), W.begin());
    apply_hair_widths(cs, {});
    const auto kept = cs.find<float>(Domain::Point, attr::width);
    EXPECT_EQ(std::vector<float>(kept.begin(), kept.end()), mine);

    // Either option given rewrites the whole taper; the other end takes its default.
    HairWidths only_root;
    only_root.root = 0.02f;
    apply_hair_widths(cs, only_root);
    expect_linear_taper(cs, 0.02f, kDefaultTipWidthCm);
    HairWidths only_tip;
    only_tip.tip = 0.0f;
    apply_hair_widths(cs, only_tip);
    expect_linear_taper(cs, kDefaultRootWidthCm, 0.0f);

    // A width per curve (USD uniform widths) is the input's width: kept, per point.
    CurveSet uniform = make_curves({uneven(3, {0, 0, 0}), uneven(4, {0, 1, 0})});
    auto cw = uniform.add<float>(Domain::Curve, attr::width);
    cw[0] = 0.25f, cw[1] = 0.5f;
    apply_hair_widths(uniform, {});
    EXPECT_TRUE(uniform.find<float>(Domain::Curve, attr::width).empty());
    const auto pw = uniform.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(pw.size(), 7u);
    EXPECT_EQ(pw[2], 0.25f);
    EXPECT_EQ(pw[3], 0.5f);
}

TEST(HairWidths, ValidateNamesTheOptionAndTheValue)
{
    auto message = [](HairWidths w) {
        try {
            w.validate("curl");
        }
        catch (const InvalidParam& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    HairWidths w;
    EXPECT_EQ(message(w), "");
    w.root = 0.0f;
    EXPECT_EQ(message(w), "curl: --root-width must be a finite number > 0 and <= 1e+06 (got 0)");
    w.root = std::nanf("");
    EXPECT_NE(message(w).find("--root-width"), std::string::npos);
    w.root = 0.01f;
    w.tip = -1.0f;
    EXPECT_EQ(message(w), "curl: --tip-width must be a finite number >= 0 and <= 1e+06 (got -1)");
    w.tip = 0.0f;
    EXPECT_EQ(message(w), "");
}
