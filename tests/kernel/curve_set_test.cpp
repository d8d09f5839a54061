#include "kernel/curve_set.h"
#include "kernel/error.h"

#include <gtest/gtest.h>

#include <limits>

#include <cmath>

using namespace groom;

TEST(CurveSet, FromCountsBuildsOffsetsAndSizesColumns)
{
    const std::vector<int64_t> counts{3, 0, 5};
    CurveSet cs = CurveSet::from_counts(counts);
    EXPECT_EQ(cs.num_curves(), 3u);
    EXPECT_EQ(cs.num_points(), 8u);
    EXPECT_EQ(cs.points_of(2).begin, 3);
    EXPECT_EQ(cs.points_of(2).end, 8);
    EXPECT_EQ(cs.positions().size(), 8u);
    auto w = cs.add<float>(Domain::Point, attr::width);
    auto id = cs.add<int64_t>(Domain::Curve, attr::id);
    EXPECT_EQ(w.size(), 8u);
    EXPECT_EQ(id.size(), 3u);
    EXPECT_NO_THROW(cs.validate());
}

TEST(CurveSet, AddingExistingNameWithOtherTypeThrows)
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{2});
    cs.add<float>(Domain::Point, "w");
    EXPECT_THROW(cs.add<int32_t>(Domain::Point, "w"), InvalidGeometry);
    EXPECT_EQ(cs.add<float>(Domain::Point, "w").size(), 2u);  // same type returns the existing column
}

TEST(CurveSet, StringsOnlyOnDetailDomain)
{
    CurveSet cs;
    EXPECT_THROW(cs.attributes(Domain::Point).add("name", Domain::Point, AttrType::String, 0), InvalidGeometry);
    cs.set_detail_string("hair_type", "3a");
    EXPECT_EQ(cs.detail_string("hair_type"), "3a");
}

TEST(CurveSet, ValidateRejectsNonFinitePositionsNamingThePoint)
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{2, 2});
    cs.positions_for_write()[3] = float3(0, NAN, 0);
    try {
        cs.validate("guides.usda");
        FAIL() << "expected InvalidGeometry";
    }
    catch (const InvalidGeometry& e) {
        EXPECT_NE(std::string(e.what()).find("guides.usda: point 3 (curve 1)"), std::string::npos) << e.what();
    }
}

// validate() tests positions and widths on their bits (so the check vectorises): every value a
// float can hold is judged as the plain comparisons judge it, the edge cases included.
TEST(CurveSet, ValidateJudgesEveryKindOfFloatLikeThePlainComparisons)
{
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float big = std::numeric_limits<float>::max(), tiny = std::numeric_limits<float>::denorm_min();
    const float values[] = {0.0f, -0.0f, tiny, -tiny, 1.0f, -1.0f, big, -big, inf, -inf, nan, -nan};
    for (const float v : values) {
        for (const size_t at : {size_t(0), size_t(13), size_t(40)}) {  // inside and at the end of vector lanes
            CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{20, 21});
            auto P = cs.positions_for_write();
            auto W = cs.add<float>(Domain::Point, attr::width);
            for (size_t i = 0; i < P.size(); ++i) P[i] = float3(float(i), 1.0f, 2.0f), W[i] = 0.01f;
            P[at].y = v;
            const bool position_ok = std::isfinite(v);
            bool threw = false;
            try {
                cs.validate();
            }
            catch (const InvalidGeometry& e) {
                threw = true;
                EXPECT_NE(std::string(e.what()).find("point " + std::to_string(at)), std::string::npos) << e.what();
            }
            EXPECT_EQ(threw, !position_ok) << "position " << v << " at " << at;
            P[at].y = 1.0f;
            W[at] = v;
            const bool width_ok = std::isfinite(v) && v >= 0.0f;
            threw = false;
            try {
                cs.validate();
            }
            catch (const InvalidGeometry& e) {
                threw = true;
                EXPECT_NE(std::string(e.what()).find("point " + std::to_string(at)), std::string::npos) << e.what();
            }
            EXPECT_EQ(threw, !width_ok) << "width " << v << " at " << at;
        }
    }
}

TEST(CurveSet, ValidateRejectsColumnSizeMismatch)
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{2});
    cs.attributes(Domain::Curve).add("bad", Domain::Curve, AttrType::Float, 5);
    EXPECT_THROW(cs.validate(), InvalidGeometry);
}

TEST(CurveSet, SetOffsetsRejectsDecreasingOffsets)
{
    CurveSet cs;
    EXPECT_THROW(cs.set_offsets({0, 3, 2}), InvalidGeometry);
    EXPECT_THROW(cs.set_offsets({1, 3}), InvalidGeometry);
}

TEST(CurveSet, CurveIdsFallBackToIndex)
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{1, 1, 1});
    EXPECT_EQ(cs.curve_ids(), (std::vector<int64_t>{0, 1, 2}));
    auto id = cs.add<int32_t>(Domain::Curve, attr::id);
    id[0] = 7; id[1] = 8; id[2] = 9;
    EXPECT_EQ(cs.curve_ids(), (std::vector<int64_t>{7, 8, 9}));
}

TEST(CurveSet, CarryAttributesGathersBySourceIndex)
{
    CurveSet src = CurveSet::from_counts(std::vector<int64_t>{2, 2});
    auto g = src.add<float3>(Domain::Curve, "Cd");
    g[0] = {1, 0, 0};
    g[1] = {0, 1, 0};
    auto pw = src.add<float>(Domain::Point, attr::width);
    for (size_t i = 0; i < 4; ++i) pw[i] = float(i);
    src.set_detail_string("note", "x");

    CurveSet dst = CurveSet::from_counts(std::vector<int64_t>{1, 1, 1});
    const std::vector<int64_t> from{1, 1, 0};
    carry_curve_attributes(src, dst, from);
    auto cd = dst.find<float3>(Domain::Curve, "Cd");
    ASSERT_EQ(cd.size(), 3u);
    EXPECT_EQ(cd[0], float3(0, 1, 0));
    EXPECT_EQ(cd[2], float3(1, 0, 0));
    EXPECT_EQ(dst.detail_string("note"), "x");

    const std::vector<int64_t> pfrom{3, 0, 2};
    carry_point_attributes(src, dst, pfrom, {attr::P});
    auto dw = dst.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(dw.size(), 3u);
    EXPECT_EQ(dw[0], 3.0f);
    EXPECT_EQ(dw[2], 2.0f);
}
