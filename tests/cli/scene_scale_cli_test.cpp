// Scene units against the centimetre defaults (cli/scene_scale.h): a head in metres (a sphere of
// radius 0.1, the size of a cranium in metres) with the defaults gets a warning naming
// --units-per-cm from `generate` (default widths) and `curl` (a default radius longer than the
// hairs), none with --units-per-cm 0.01, which also scales the default widths; `cornrow-guides`
// refuses its default sphere on a head whose top is not near the default head's.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "ops/hair_widths.h"
#include "support/sphere_mesh.h"

#include <cmath>

using namespace groom;
using groom::test::run_groom;
using groom::test::TempDir;

namespace {

constexpr float kR = 0.1f;  // a cranium, in metres

/// Twelve guides 6 cm long (0.06 units) rooted around the sphere's top, growing out.
std::string guides_file(const TempDir& dir)
{
    const int n = 8, g = 12;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(g, n));
    auto P = cs.positions_for_write();
    for (int k = 0; k < g; ++k) {
        const double az = 2.0 * M_PI * k / g, el = 0.5;
        const float3 up(float(std::sin(el) * std::cos(az)), float(std::cos(el)), float(std::sin(el) * std::sin(az)));
        for (int i = 0; i < n; ++i) P[k * n + i] = up * (kR * 1.001f + 0.06f * float(i) / float(n - 1));
    }
    const std::string path = dir.file("guides.usda");
    write_curves(cs, path);
    return path;
}

}  // namespace

TEST(SceneScaleCli, MetreSceneWithTheDefaultsIsWarnedAndUnitsPerCmFixesIt)
{
    TempDir dir;
    const std::string head = dir.file("head.obj");
    write_mesh(icosphere(float3(0, 0, 0), kR, 4), head);
    const std::string guides = guides_file(dir), hair = dir.file("hair.usda"), curled = dir.file("curled.usda");

    const auto warned = run_groom({"generate", guides, "--scalp", head, "--count", "200", "-o", hair});
    ASSERT_EQ(warned.exit_code, 0) << warned.err;
    EXPECT_NE(warned.err.find("generate: warning"), std::string::npos) << warned.err;
    EXPECT_NE(warned.err.find("--units-per-cm"), std::string::npos) << warned.err;

    const auto fixed = run_groom({"generate", guides, "--scalp", head, "--count", "200", "-o", hair, "--force", "--units-per-cm", "0.01"});
    ASSERT_EQ(fixed.exit_code, 0) << fixed.err;
    EXPECT_EQ(fixed.err.find("warning"), std::string::npos) << fixed.err;
    const CurveSet cs = read_curves(hair);
    const auto W = cs.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(W.size(), cs.num_points());
    EXPECT_FLOAT_EQ(W[0], kDefaultRootWidthCm * 0.01f);  // a root: 80 um in metres

    // The default 3a radius is about a centimetre: 1 unit here, longer than the 6 cm (0.06) hairs.
    const auto curl_warned = run_groom({"curl", hair, "-o", curled});
    ASSERT_EQ(curl_warned.exit_code, 0) << curl_warned.err;
    EXPECT_NE(curl_warned.err.find("curl: warning: the curl radius"), std::string::npos) << curl_warned.err;
    const auto curl_fixed = run_groom({"curl", hair, "-o", curled, "--force", "--units-per-cm", "0.01"});
    ASSERT_EQ(curl_fixed.exit_code, 0) << curl_fixed.err;
    EXPECT_EQ(curl_fixed.err.find("warning"), std::string::npos) << curl_fixed.err;
    // --quiet keeps stderr for errors.
    const auto quiet = run_groom({"curl", hair, "-o", curled, "--force", "-q"});
    EXPECT_EQ(quiet.err, "");
}

TEST(SceneScaleCli, CornrowGuidesRefuseTheirDefaultSphereOnAnotherHead)
{
    TempDir dir;
    const std::string head = dir.file("head.obj");
    write_mesh(icosphere(float3(0, 0, 0), kR, 4), head);
    const std::string out = dir.file("rows.usda");
    const auto refused = run_groom({"cornrow-guides", "--scalp", head, "-o", out});
    EXPECT_EQ(refused.exit_code, 2) << refused.err;
    EXPECT_NE(refused.err.find("--center"), std::string::npos) << refused.err;
    EXPECT_NE(refused.err.find("--radius"), std::string::npos) << refused.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    // Given for this head: rows on it (every point within a hundredth of the radius of the sphere).
    const auto ok = run_groom({"cornrow-guides", "--scalp", head, "-o", out, "--center", "0,0,0", "--radius", "0.1", "--pivot", "0.075"});
    ASSERT_EQ(ok.exit_code, 0) << ok.err;
    const CurveSet rows = read_curves(out);
    ASSERT_GT(rows.num_points(), 0u);
    for (const float3& p : rows.positions()) EXPECT_NEAR(length(p), kR, 0.01f * kR);
}
