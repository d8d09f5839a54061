// Container operations: join and remove_curves carry every column, fill what one side lacks, and
// keep order.
#include "kernel/curve_set_edit.h"

#include <gtest/gtest.h>

using namespace groom;

TEST(CurveSetEdit, JoinFillsMissingColumns)
{
    CurveSet a = CurveSet::from_counts(std::vector<int64_t>{2, 3});
    CurveSet b = CurveSet::from_counts(std::vector<int64_t>{4});
    a.add<int32_t>(Domain::Curve, "kind")[1] = 7;
    b.add<int32_t>(Domain::Curve, "kind")[0] = 1;
    b.add<int32_t>(Domain::Point, "shape")[3] = 4;
    a.add<float>(Domain::Point, "width")[0] = 0.5f;
    b.positions_for_write()[2] = float3(1, 2, 3);
    b.set_detail_string("hair_type", "4a");
    const CurveSet j = join(a, b);
    ASSERT_EQ(j.num_curves(), 3u);
    ASSERT_EQ(j.num_points(), 9u);
    EXPECT_EQ(j.positions()[7], float3(1, 2, 3));
    const auto kind = j.find<int32_t>(Domain::Curve, "kind");
    EXPECT_EQ(kind[0], 0);
    EXPECT_EQ(kind[1], 7);
    EXPECT_EQ(kind[2], 1);
    const auto shape = j.find<int32_t>(Domain::Point, "shape");
    EXPECT_EQ(shape[0], -1);
    EXPECT_EQ(shape[8], 4);
    EXPECT_EQ(j.find<float>(Domain::Point, "width")[0], 0.5f);
    EXPECT_EQ(j.find<float>(Domain::Point, "width")[8], 0.0f);
    EXPECT_EQ(j.detail_string("hair_type"), "4a");
    EXPECT_NO_THROW(j.validate());
    b.add<float>(Domain::Curve, "clump");
    a.add<int32_t>(Domain::Curve, "clump");
    EXPECT_THROW(join(a, b), InvalidGeometry);
}

TEST(CurveSetEdit, RemoveCurvesCarriesEveryColumn)
{
    CurveSet src = CurveSet::from_counts(std::vector<int64_t>{2, 3, 1, 0});
    auto P = src.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = float3(float(i), 0, 0);
    auto w = src.add<float>(Domain::Point, "width");
    for (size_t i = 0; i < w.size(); ++i) w[i] = 0.5f * float(i);
    auto id = src.add<int64_t>(Domain::Curve, "id");
    for (size_t c = 0; c < id.size(); ++c) id[c] = 10 + int64_t(c);
    src.set_detail_string("hair_type", "3c");
    const std::vector<char> remove{0, 1, 0, 0};
    std::vector<int64_t> kept;
    const CurveSet dst = remove_curves(src, remove, &kept);
    EXPECT_EQ(kept, (std::vector<int64_t>{0, 2, 3}));
    ASSERT_EQ(dst.num_curves(), 3u);
    ASSERT_EQ(dst.num_points(), 3u);
    // Curve 0 keeps points 0 and 1; curve 2 (now 1) is source point 5; the empty curve stays empty.
    EXPECT_EQ(dst.positions()[0], float3(0, 0, 0));
    EXPECT_EQ(dst.positions()[1], float3(1, 0, 0));
    EXPECT_EQ(dst.positions()[2], float3(5, 0, 0));
    EXPECT_EQ(dst.find<float>(Domain::Point, "width")[2], 2.5f);
    EXPECT_EQ(dst.points_in(2), 0);
    const auto out_id = dst.find<int64_t>(Domain::Curve, "id");
    EXPECT_EQ(out_id[0], 10);
    EXPECT_EQ(out_id[1], 12);
    EXPECT_EQ(out_id[2], 13);
    EXPECT_EQ(dst.detail_string("hair_type"), "3c");
    EXPECT_NO_THROW(dst.validate());
    EXPECT_THROW(remove_curves(src, std::vector<char>{1, 0}), InvalidParam);
}
