// select: exactly the curves asked for, by id range, guide, attribute comparison and prim path;
// invert keeps the complement; attributes carried; bad expressions named.
#include "ops/select.h"

#include "kernel/error.h"
#include "kernel/parallel.h"
#include "ops/make_curves.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace groom;

namespace {

/// Ten straight two-point curves, curve c at x = c, with ids 100 + 10 c, guide c % 3, kind c % 2
/// and a root width of 0.001 * c.
CurveSet ten_curves()
{
    std::vector<std::vector<float3>> pts;
    for (int c = 0; c < 10; ++c) pts.push_back({float3(float(c), 0, 0), float3(float(c), 1, 0)});
    CurveSet cs = test::make_curves(pts);
    auto id = cs.add<int64_t>(Domain::Curve, attr::id);
    auto guide = cs.add<int32_t>(Domain::Curve, "guide");
    auto kind = cs.add<int32_t>(Domain::Curve, "kind");
    auto width = cs.add<float>(Domain::Point, attr::width);
    auto cd = cs.add<float3>(Domain::Curve, "Cd");
    for (int c = 0; c < 10; ++c) {
        id[c] = 100 + 10 * c;
        guide[c] = c % 3;
        kind[c] = c % 2;
        width[2 * c] = 0.001f * float(c);
        width[2 * c + 1] = 0.0f;
        cd[c] = float3(0.1f * float(c), 0, 0);
    }
    return cs;
}

std::vector<int64_t> ids_of(const CurveSet& cs) { return cs.curve_ids(); }

}  // namespace

TEST(Select, IdRangeKeepsExactlyThoseIds)
{
    const CurveSet src = ten_curves();
    SelectParams p;
    p.ids = parse_id_ranges("120-140,190");
    SelectStats stats;
    const CurveSet out = select(src, p, &stats);
    EXPECT_EQ(ids_of(out), (std::vector<int64_t>{120, 130, 140, 190}));
    EXPECT_EQ(stats.matched, 4);
    EXPECT_EQ(stats.kept, 4);
    // Points and every column carried with their curve.
    ASSERT_EQ(out.num_points(), 8u);
    EXPECT_EQ(out.positions()[0], float3(2, 0, 0));
    EXPECT_EQ(out.positions()[7], float3(9, 1, 0));
    EXPECT_EQ(out.find<int32_t>(Domain::Curve, "guide")[3], 0);
    EXPECT_FLOAT_EQ(out.find<float>(Domain::Point, attr::width)[6], 0.009f);
}

TEST(Select, InvertKeepsTheComplement)
{
    const CurveSet src = ten_curves();
    SelectParams p;
    p.ids = parse_id_ranges("120-140,190");
    p.invert = true;
    EXPECT_EQ(ids_of(select(src, p)), (std::vector<int64_t>{100, 110, 150, 160, 170, 180}));
}

TEST(Select, CurvesWithoutIdsAreSelectedByIndex)
{
    CurveSet src = ten_curves();
    src.attributes(Domain::Curve).remove(attr::id);
    SelectParams p;
    p.ids = parse_id_ranges("3-5");
    const CurveSet out = select(src, p);
    ASSERT_EQ(out.num_curves(), 3u);
    EXPECT_EQ(out.positions()[0].x, 3.0f);
    EXPECT_EQ(out.positions()[4].x, 5.0f);
}

TEST(Select, GuideAndAttributeComparisonsAllMustHold)
{
    const CurveSet src = ten_curves();
    SelectParams p;
    p.guides = {1, 2};                                // curves 1 2 4 5 7 8
    p.where = {parse_attribute_test("kind==1")};      // curves 1 3 5 7 9
    EXPECT_EQ(ids_of(select(src, p)), (std::vector<int64_t>{110, 150, 170}));
    // A point attribute is read at the root: widths 0.001 c.
    p = {};
    p.where = {parse_attribute_test("width > 0.0065")};
    EXPECT_EQ(ids_of(select(src, p)), (std::vector<int64_t>{170, 180, 190}));
    p.where = {parse_attribute_test("width>=0.0065"), parse_attribute_test("Cd.x<0.85")};
    EXPECT_EQ(ids_of(select(src, p)), (std::vector<int64_t>{170, 180}));
    p.where = {parse_attribute_test("kind!=0"), parse_attribute_test("id<=130")};
    EXPECT_EQ(ids_of(select(src, p)), (std::vector<int64_t>{110, 130}));
}

TEST(Select, PrimPathSelectsThePrimAndWhatIsUnderIt)
{
    CurveSet src = ten_curves();
    auto prim = src.add<int32_t>(Domain::Curve, "prim");
    for (int c = 0; c < 10; ++c) prim[c] = c < 3 ? 0 : c < 6 ? 1 : 2;
    src.set_detail_string("prim_paths", "/Root/Hair\n/Root/Hair/Fringe\n/Root/HairBack");
    SelectParams p;
    p.prims = {"/Root/Hair"};
    EXPECT_EQ(ids_of(select(src, p)), (std::vector<int64_t>{100, 110, 120, 130, 140, 150}));
    p.prims = {"/Root/Hair/Fringe", "/Root/HairBack"};
    EXPECT_EQ(ids_of(select(src, p)), (std::vector<int64_t>{130, 140, 150, 160, 170, 180, 190}));
    // Curves without prim paths: an error naming the option, not an empty result.
    p.prims = {"/Root"};
    EXPECT_THROW(select(ten_curves(), p), InvalidParam);
}

TEST(Select, ParsesIdRangesWithNegativeIds)
{
    const auto r = parse_id_ranges("-9--5, -2,3-4");
    ASSERT_EQ(r.size(), 3u);
    EXPECT_EQ(r[0].lo, -9);
    EXPECT_EQ(r[0].hi, -5);
    EXPECT_EQ(r[1].lo, -2);
    EXPECT_EQ(r[1].hi, -2);
    EXPECT_EQ(r[2].lo, 3);
    EXPECT_EQ(r[2].hi, 4);
}

TEST(Select, RejectsBadExpressionsNamingTheOptionAndWhatWasExpected)
{
    auto message = [](auto&& fn) {
        try {
            fn();
        }
        catch (const InvalidParam& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    for (const char* bad : {"width", "width>", ">3", "width>abc", "width=>3", "Cd.w<1", "wi dth<1", "width<nan"}) {
        const std::string m = message([&] { parse_attribute_test(bad); });
        EXPECT_NE(m.find("`where`"), std::string::npos) << bad << ": " << m;
        EXPECT_NE(m.find("expected NAME OP NUMBER"), std::string::npos) << bad << ": " << m;
    }
    for (const char* bad : {"", "1-", "a-3", "5-3", "1,,2", "1.5"}) {
        const std::string m = message([&] { parse_id_ranges(bad); });
        EXPECT_NE(m.find("`ids`"), std::string::npos) << bad << ": " << m;
        EXPECT_NE(m.find("expected a comma-separated list"), std::string::npos) << bad << ": " << m;
    }
    // An attribute the curves lack names the ones they have.
    SelectParams p;
    p.where = {parse_attribute_test("thickness>0")};
    const std::string m = message([&] { select(ten_curves(), p); });
    EXPECT_NE(m.find("'thickness'"), std::string::npos) << m;
    EXPECT_NE(m.find("width (point)"), std::string::npos) << m;
    p.where = {parse_attribute_test("Cd>0")};
    EXPECT_NE(message([&] { select(ten_curves(), p); }).find("name a component"), std::string::npos);
    // Nothing to select by.
    EXPECT_NE(message([&] { select(ten_curves(), SelectParams{}); }).find("nothing to select by"), std::string::npos);
    // --guide on curves without a guide column.
    CurveSet no_guide = ten_curves();
    no_guide.attributes(Domain::Curve).remove("guide");
    p = {};
    p.guides = {1};
    EXPECT_NE(message([&] { select(no_guide, p); }).find("`guide` needs"), std::string::npos);
}

TEST(Select, SameOutputForAnyThreadCount)
{
    std::vector<std::vector<float3>> pts;
    for (int c = 0; c < 5000; ++c) pts.push_back({float3(float(c), 0, 0), float3(float(c), 1, float(c % 7))});
    CurveSet src = test::make_curves(pts);
    auto w = src.add<float>(Domain::Point, attr::width);
    for (size_t i = 0; i < w.size(); ++i) w[i] = float(i % 13) * 0.001f;
    SelectParams p;
    p.ids = parse_id_ranges("10-4000");
    p.where = {parse_attribute_test("width<0.006")};
    CurveSet one, all;
    {
        ThreadLimit limit(1);
        one = select(src, p);
    }
    all = select(src, p);
    ASSERT_EQ(one.num_points(), all.num_points());
    EXPECT_GT(one.num_curves(), 1000u);
    EXPECT_EQ(0, std::memcmp(one.positions().data(), all.positions().data(), one.num_points() * sizeof(float3)));
}
