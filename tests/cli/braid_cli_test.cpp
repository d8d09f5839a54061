// `groom braid` and `groom populate` end to end: files in, files out, exit codes and messages.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/math/polyline.h"

#include <cmath>
#include <fstream>
#include <numbers>
#include <set>

using namespace groom;
using groom::test::run_groom;
using groom::test::TempDir;

namespace {

/// Two straight guides and a bent one, as OBJ polylines.
std::string guides_obj(const TempDir& dir)
{
    const std::string path = dir.file("guides.obj");
    groom::test::write_text(path,
                            "v 0 0 0\nv 0 5 0\nv 0 10 0\nv 0 15 0\n"
                            "v 3 0 0\nv 3 5 0\nv 3 10 0\nv 3 12 0\n"
                            "v 6 0 0\nv 6 5 1\nv 7 10 2\nv 9 14 3\n"
                            "l 1 2 3 4\nl 5 6 7 8\nl 9 10 11 12\n");
    return path;
}

}  // namespace

TEST(PopulateCli, FillsADiscAroundEachCurve)
{
    TempDir dir;
    const std::string in = guides_obj(dir), out = dir.file("pop.usda");
    const auto r = run_groom({"populate", in, "-o", out, "--count", "25", "--radius", "0.3", "--seed", "2"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet src = read_curves(in), cs = read_curves(out);
    ASSERT_EQ(cs.num_curves(), 75u);
    const auto fiber = cs.find<int32_t>(Domain::Curve, "fiber");
    ASSERT_EQ(fiber.size(), 75u);
    // Guide 0 is the straight +Y line through the origin: its fibers are within 0.3 of it.
    for (size_t c = 0; c < 25; ++c) {
        EXPECT_EQ(fiber[c], int32_t(c));
        for (int64_t q = cs.points_of(c).begin; q < cs.points_of(c).end; ++q) {
            const float3 p = cs.positions()[q];
            EXPECT_LE(std::hypot(p.x, p.z), 0.3f + 1e-5f);
        }
    }
    const auto bad = run_groom({"populate", in, "-o", out, "--count", "0", "--radius", "1", "--force"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("populate: --count must be in [1, 1000000] (got 0)"), std::string::npos) << bad.err;
}
