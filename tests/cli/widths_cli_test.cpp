// Widths everywhere: every command that makes hairs writes a per-point `width` tapered from
// --root-width to --tip-width (ops/hair_widths.h), checked from the files it writes; .hair thickness
// and .usda widths carry it; an input's widths are kept unless the options are given.
#include "test_support.h"
#include "sphere_scalp.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "ops/hair_widths.h"
#include "support/sphere_mesh.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <cmath>
#include <functional>

using namespace groom;
using groom::test::read_bytes;
using groom::test::run_groom;
using groom::test::TempDir;

namespace {

constexpr float kR = test::kSphereScalpRadius;
using test::sphere_scalp;

/// Eight guides rooted on the sphere 30 degrees from its top, growing out and down, 12 points each;
/// with `width`, a point width 0.02 at the root falling to 0.01 at the tip by point index.
std::string guides_file(const TempDir& dir, const std::string& name, bool width)
{
    const int n = 12, g = 8;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(g, n));
    auto P = cs.positions_for_write();
    std::span<float> W;
    if (width) W = cs.add<float>(Domain::Point, attr::width);
    for (int k = 0; k < g; ++k) {
        const double az = 2.0 * M_PI * k / g, el = M_PI / 6;
        const float3 up(float(std::sin(el) * std::cos(az)), float(std::cos(el)), float(std::sin(el) * std::sin(az)));
        for (int i = 0; i < n; ++i) {
            const float t = float(i) / float(n - 1);
            P[k * n + i] = up * (kR * 1.0005f + 4.0f * t) - float3(0, 3.0f * t * t, 0);
            if (width) W[k * n + i] = 0.02f - 0.01f * t;
        }
    }
    const std::string path = dir.file(name);
    write_curves(cs, path);
    return path;
}

/// Every point has a width; in curves passing `select`, the root's is `root` and the tip's `tip`
/// exactly, and widths never turn back on the way.
void expect_taper(const CurveSet& cs, float root, float tip, const std::string& what,
                  const std::function<bool(size_t)>& select = [](size_t) { return true; })
{
    const auto W = cs.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(W.size(), cs.num_points()) << what << ": no point width";
    size_t checked = 0;
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        if (!select(c)) continue;
        const IndexRange r = cs.points_of(c);
        if (r.size() < 2) continue;
        ++checked;
        ASSERT_EQ(W[r.begin], root) << what << " curve " << c;
        ASSERT_EQ(W[r.end - 1], tip) << what << " curve " << c;
        for (int64_t i = r.begin + 1; i < r.end; ++i) {
            if (root >= tip) ASSERT_LE(W[i], W[i - 1]) << what << " curve " << c << " point " << i - r.begin;
            else ASSERT_GE(W[i], W[i - 1]) << what << " curve " << c << " point " << i - r.begin;
        }
    }
    EXPECT_GT(checked, 0u) << what;
}

/// Runs groom with `args`, expecting success, and reads `out`.
CurveSet run_and_read(const std::vector<std::string>& args, const std::string& out)
{
    const auto r = run_groom(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_curves(out);
}

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more)
{
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

}  // namespace

TEST(WidthsCli, EveryCommandThatMakesHairsTapersRootToTip)
{
    TempDir dir;
    // One field for every command, as a user's script does.
    const std::string scalp = dir.file("head.vdb");
    ASSERT_EQ(run_groom({"scalp", sphere_scalp(dir), "-o", scalp}).exit_code, 0);
    const std::string guides = guides_file(dir, "guides.usda", false), out = dir.file("out.usda");
    const std::vector<std::string> given{"--root-width", "0.012", "--tip-width", "0.002"};

    struct Case {
        std::string name;
        std::vector<std::string> args;
        std::function<bool(size_t)> hairs;  // which output curves are hairs (gather's bands are not)
    };
    const std::string puff = dir.file("puff.usda");
    ASSERT_EQ(run_groom({"puff", "--scalp", scalp, "-o", puff, "--center", "0,12,0", "--radius", "3", "--sphere-center", "0,15,0",
                         "--sphere-radius", "6", "--rows", "3", "--cols", "3", "--hairs", "40", "--amplitude", "0.1,0.2"})
                  .exit_code,
              0);
    const CurveSet puffed = read_curves(puff);
    const std::vector<Case> cases{
        {"curl", {"curl", guides, "-o", out, "--amplitude", "0.1,0.2"}, nullptr},
        {"generate", {"generate", guides, "--scalp", scalp, "-o", out, "--count", "50"}, nullptr},
        {"puff", {"puff", "--scalp", scalp, "-o", out, "--center", "0,12,0", "--radius", "3", "--sphere-center", "0,15,0", "--sphere-radius",
                  "6", "--rows", "3", "--cols", "3", "--hairs", "40", "--amplitude", "0.1,0.2"},
         nullptr},
        {"edges", {"edges", "--scalp", scalp, "-o", out, "--count", "30"}, nullptr},
        {"partition", {"partition", guides, "--scalp", scalp, "-o", out, "--count", "3"}, nullptr},
        {"populate", {"populate", guides, "-o", out, "--count", "4", "--radius", "0.1"}, nullptr},
    };
    for (const Case& k : cases) {
        SCOPED_TRACE(k.name);
        if (k.name != "populate") {  // populate's own default is its automatic fiber width
            const CurveSet d = run_and_read(k.args, out);
            expect_taper(d, kDefaultRootWidthCm, kDefaultTipWidthCm, k.name + " (defaults)");
        }
        const CurveSet g = run_and_read(with(k.args, given), out);
        expect_taper(g, 0.012f, 0.002f, k.name + " (given)");
    }

    // gather: its hairs taper over their whole length; its bands keep the band thickness.
    const std::vector<std::string> gather{"gather", puff, "--scalp", scalp, "-o", out, "--hairs", "60", "--type", "4a"};
    CurveSet g = run_and_read(gather, out);
    auto is_hair = [&g](size_t c) { return g.find<int32_t>(Domain::Curve, "kind")[c] == 1; };
    expect_taper(g, kDefaultRootWidthCm, kDefaultTipWidthCm, "gather (defaults)", is_hair);
    g = run_and_read(with(gather, given), out);
    expect_taper(g, 0.012f, 0.002f, "gather (given)", is_hair);
    const auto kind = g.find<int32_t>(Domain::Curve, "kind");
    const auto W = g.find<float>(Domain::Point, attr::width);
    for (size_t c = 0; c < g.num_curves(); ++c)
        if (kind[c] == 2) EXPECT_EQ(W[g.points_of(c).begin], 0.12f);  // --band-thickness default
    (void)puffed;
}

TEST(WidthsCli, InputWidthsAreKeptUnlessTheOptionsAreGiven)
{
    TempDir dir;
    const std::string guides = guides_file(dir, "wide.usda", true), out = dir.file("out.usda");
    // curl interpolates the input's widths: the root keeps 0.02, every width stays within the
    // input's [0.01, 0.02] and falls toward the tip.
    const CurveSet c = run_and_read({"curl", guides, "-o", out, "--amplitude", "0.1,0.2"}, out);
    const auto W = c.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(W.size(), c.num_points());
    for (size_t k = 0; k < c.num_curves(); ++k) {
        const IndexRange r = c.points_of(k);
        EXPECT_EQ(W[r.begin], 0.02f);
        for (int64_t i = r.begin; i < r.end; ++i) {
            ASSERT_GE(W[i], 0.01f - 1e-7f);
            ASSERT_LE(W[i], 0.02f);
            if (i > r.begin) ASSERT_LE(W[i], W[i - 1] + 1e-7f);
        }
    }
    // Given, the options win.
    expect_taper(run_and_read({"curl", guides, "-o", out, "--root-width", "0.005", "--tip-width", "0.001"}, out), 0.005f, 0.001f,
                 "curl over input widths");
    // Bad values are usage errors naming the option; nothing is written.
    const auto r = run_groom({"curl", guides, "-o", dir.file("bad.usda"), "--root-width", "0"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--root-width must be a finite number > 0"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("bad.usda")));
    const auto r2 = run_groom({"populate", guides, "-o", dir.file("bad.usda"), "--width", "0.1", "--tip-width", "0.01"});
    EXPECT_NE(r2.exit_code, 0);
    EXPECT_NE(r2.err.find("exclusive"), std::string::npos) << r2.err;
}

TEST(WidthsCli, HairThicknessAndUsdaWidthsCarryTheTaper)
{
    TempDir dir;
    const std::string guides = guides_file(dir, "guides.usda", false), usda = dir.file("c.usda"), hair = dir.file("c.hair");
    const CurveSet c = run_and_read({"curl", guides, "-o", usda, "--root-width", "0.01", "--tip-width", "0.003"}, usda);
    // USD: per-point `widths` (a diameter, as USD defines it).
    const std::string text = read_bytes(usda);
    const size_t at = text.find("float[] widths = [");
    ASSERT_NE(at, std::string::npos);
    EXPECT_NE(text.find("interpolation = \"vertex\"", at), std::string::npos);
    // .hair: per-point thickness (flag 4), the same floats.
    ASSERT_EQ(run_groom({"convert", usda, "-o", hair}).exit_code, 0);
    const std::string bytes = read_bytes(hair);
    uint32_t flags = 0;
    std::memcpy(&flags, bytes.data() + 12, 4);
    EXPECT_TRUE(flags & 4u);
    const CurveSet back = read_curves(hair);
    const auto a = c.find<float>(Domain::Point, attr::width), b = back.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin()));
    expect_taper(back, 0.01f, 0.003f, ".hair read back");
}
