// `groom probe` end to end: text, .npy and curve-file inputs give the same CSV byte for byte, for
// --threads 1 and 2; `-o .npy` holds the same numbers; answers around an analytic sphere within
// the tessellation's bounds; bad inputs name the file.
#include "test_support.h"

#include "kernel/io/point_table.h"
#include "sphere_scalp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace groom {
namespace {

using test::read_bytes;
using test::run_groom;
using test::TempDir;
using test::write_text;

std::string num(float v)
{
    char buf[32];
    return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

/// Points around the sphere of radius R at the origin: 400 directions (a Fibonacci spiral) at 8
/// radii from 0.7 R (inside) to 1.9 R, in and far outside the band.
std::vector<float3> sphere_points(float R)
{
    std::vector<float3> pts;
    const float offsets[] = {-3.0f, -0.5f, -0.04f, 0.02f, 0.3f, 1.0f, 4.0f, 9.0f};
    for (int i = 0; i < 400; ++i) {
        const float z = 1.0f - 2.0f * (float(i) + 0.5f) / 400.0f, r = std::sqrt(1.0f - z * z), phi = 2.39996323f * float(i);
        const float3 dir(r * std::cos(phi), r * std::sin(phi), z);
        for (float o : offsets) pts.push_back(dir * (R + o));
    }
    return pts;
}

std::vector<std::vector<double>> read_csv(const std::string& text)
{
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "x,y,z,distance,nx,ny,nz,cx,cy,cz");
    std::vector<std::vector<double>> rows;
    while (std::getline(in, line)) {
        std::vector<double> v;
        std::stringstream ss(line);
        for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
        EXPECT_EQ(v.size(), 10u) << line;
        rows.push_back(v);
    }
    return rows;
}

TEST(ProbeCli, TextNpyAndCurvesGiveTheSameBytesForAnyThreadCount)
{
    TempDir dir;
    const std::string head = test::sphere_scalp(dir);
    const std::vector<float3> pts = sphere_points(test::kSphereScalpRadius);
    std::string text = "# x y z\n", obj;
    std::vector<float> flat;
    for (size_t i = 0; i < pts.size(); ++i) {
        const float3& p = pts[i];
        text += num(p.x) + ", " + num(p.y) + ", " + num(p.z) + "\n";
        obj += "v " + num(p.x) + " " + num(p.y) + " " + num(p.z) + "\n";
        flat.insert(flat.end(), {p.x, p.y, p.z});
    }
    for (size_t c = 0; c < pts.size() / 8; ++c) {  // one 8-point curve per direction
        obj += "l";
        for (size_t k = 1; k <= 8; ++k) obj += " " + std::to_string(c * 8 + k);
        obj += "\n";
    }
    write_text(dir.file("p.txt"), text);
    write_text(dir.file("p.obj"), obj);
    std::ostringstream npy;
    write_npy_table(npy, flat, 3);
    write_text(dir.file("p.npy"), npy.str());

    std::string reference;
    for (const std::string in : {"p.txt", "p.npy", "p.obj"}) {
        for (const char* threads : {"1", "2"}) {
            const auto r = run_groom({"probe", "--scalp", head, dir.file(in), "-o", dir.file("o.csv"), "--threads", threads, "-q", "--force"});
            ASSERT_EQ(r.exit_code, 0) << r.err;
            const std::string bytes = read_bytes(dir.file("o.csv"));
            if (reference.empty()) reference = bytes;
            EXPECT_EQ(bytes, reference) << in << " --threads " << threads;
        }
    }

    // -o .npy: (N, 10) float32 holding the CSV's numbers exactly.
    ASSERT_EQ(run_groom({"probe", "--scalp", head, dir.file("p.txt"), "-o", dir.file("o.npy"), "-q"}).exit_code, 0);
    const std::string out = read_bytes(dir.file("o.npy"));
    ASSERT_GT(out.size(), 10u);
    const size_t header = size_t(uint8_t(out[8])) | size_t(uint8_t(out[9])) << 8;
    EXPECT_NE(out.find("'shape': (3200, 10)"), std::string::npos);
    ASSERT_EQ(out.size(), 10 + header + pts.size() * 10 * 4);
    const auto rows = read_csv(reference);
    ASSERT_EQ(rows.size(), pts.size());
    for (size_t i = 0; i < rows.size(); ++i) {
        for (size_t k = 0; k < 10; ++k) {
            float v;
            std::memcpy(&v, out.data() + 10 + header + (i * 10 + k) * 4, 4);
            ASSERT_EQ(v, float(rows[i][k])) << i << " " << k;
        }
    }
}

TEST(ProbeCli, AnswersAroundTheSphereWithinTheTessellationsBounds)
{
    TempDir dir;
    const std::string head = test::sphere_scalp(dir);
    const float R = test::kSphereScalpRadius;
    const PolygonSoup soup = icosphere(float3(0, 0, 0), R, 4);
    const float chord = sphere_chordal_error(soup, float3(0, 0, 0), R);
    // The largest angle between a face's normal and the radius through its vertices: a closest
    // point at distance t on a facet lies up to t sin(alpha) sideways of the radial projection.
    double alpha = 0.0;
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        const auto face = soup.face(f);
        const float3 a = soup.points[face[0]], b = soup.points[face[1]], c = soup.points[face[2]];
        const float3 n = normalize(cross(b - a, c - a));
        for (const float3& v : {a, b, c}) alpha = std::max(alpha, std::acos(std::min(1.0, double(dot(n, normalize(v))))));
    }
    // Sparse points (a few a cell: ScalpField::query) and dense ones (40 radial lines of 100 points
    // from 0.3 to 1.3 out, about 27 a 2-voxel cell: query_dense), each the same for 1 and 2 threads.
    std::vector<float3> dense;
    for (int i = 0; i < 40; ++i) {
        const float z = 1.0f - 2.0f * (float(i) + 0.5f) / 40.0f, r = std::sqrt(1.0f - z * z), phi = 2.39996323f * float(i);
        for (int k = 0; k < 100; ++k) dense.push_back(float3(r * std::cos(phi), r * std::sin(phi), z) * (R + 0.3f + 0.01f * float(k)));
    }
    std::vector<std::vector<double>> rows;
    for (const std::vector<float3>& pts : {sphere_points(R), dense}) {
        std::string text;
        for (const float3& p : pts) text += num(p.x) + " " + num(p.y) + " " + num(p.z) + "\n";
        write_text(dir.file("p.txt"), text);
        std::string bytes[2];
        for (int t = 1; t <= 2; ++t) {
            const auto r = run_groom({"probe", "--scalp", head, dir.file("p.txt"), "-o", dir.file("o.csv"), "--threads", std::to_string(t), "--force"});
            ASSERT_EQ(r.exit_code, 0) << r.err;
            bytes[t - 1] = read_bytes(dir.file("o.csv"));
        }
        EXPECT_EQ(bytes[0], bytes[1]);
        const auto these = read_csv(bytes[0]);
        ASSERT_EQ(these.size(), pts.size());
        rows.insert(rows.end(), these.begin(), these.end());
    }
    // Band: the voxel is the automatic one, diagonal / 256.
    const double h = std::sqrt(3.0) * 2.0 * R / 256.0;
    for (const auto& v : rows) {
        const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        const double d = len - R;
        const double ux = v[0] / len, uy = v[1] / len, uz = v[2] / len;
        // Distance: the mesh is inscribed, within `chord` of the sphere; the band adds h^2/(2R).
        EXPECT_NEAR(v[3], d, chord + h * h / (2 * R) + 1e-4) << v[0] << "," << v[1] << "," << v[2];
        // Normal: within the facets' tilt plus the band's 2h/R of the radius.
        const double cosang = v[4] * ux + v[5] * uy + v[6] * uz;
        EXPECT_GT(cosang, std::cos(alpha + 2 * h / R)) << v[0] << "," << v[1] << "," << v[2];
        // Closest point: the radial projection, moved up to chord + |d| sin(alpha) (+ the band's h^2/R).
        const double ex = v[7] - R * ux, ey = v[8] - R * uy, ez = v[9] - R * uz;
        EXPECT_LE(std::sqrt(ex * ex + ey * ey + ez * ez), chord + std::fabs(d) * std::sin(alpha) + h * h / R + 1e-4)
            << v[0] << "," << v[1] << "," << v[2];
    }
}

TEST(ProbeCli, EachRowDependsOnItsPointAloneNotOnTheOthersOrTheirOrder)
{
    // probe queries the points sorted by cell (a counting sort over their box, or a comparison
    // sort when they spread over more than 2^20 cells): the row of a point must not depend on
    // where it is in the file, nor on the other points. Dense points (40 radial lines of 100,
    // query_dense) in the file's order, reversed, and with two points 1e6 radii out appended
    // (which takes the comparison sort and leaves the points dense) give the same rows.
    TempDir dir;
    const std::string head = test::sphere_scalp(dir);
    const float R = test::kSphereScalpRadius;
    std::vector<float3> pts;
    for (int i = 0; i < 40; ++i) {
        const float z = 1.0f - 2.0f * (float(i) + 0.5f) / 40.0f, r = std::sqrt(1.0f - z * z), phi = 2.39996323f * float(i);
        for (int k = 0; k < 100; ++k) pts.push_back(float3(r * std::cos(phi), r * std::sin(phi), z) * (R + 0.3f + 0.01f * float(k)));
    }
    const auto probe = [&](const std::vector<float3>& in) {
        std::string text;
        for (const float3& p : in) text += num(p.x) + " " + num(p.y) + " " + num(p.z) + "\n";
        write_text(dir.file("p.txt"), text);
        const auto r = run_groom({"probe", "--scalp", head, dir.file("p.txt"), "-o", dir.file("o.csv"), "--force"});
        EXPECT_EQ(r.exit_code, 0) << r.err;
        std::vector<std::string> rows;
        std::istringstream lines(read_bytes(dir.file("o.csv")));
        std::string line;
        std::getline(lines, line);
        while (std::getline(lines, line)) rows.push_back(line);
        return rows;
    };
    const std::vector<std::string> forward = probe(pts);
    ASSERT_EQ(forward.size(), pts.size());
    std::vector<float3> reversed(pts.rbegin(), pts.rend());
    std::vector<std::string> back = probe(reversed);
    ASSERT_EQ(back.size(), pts.size());
    std::reverse(back.begin(), back.end());
    EXPECT_EQ(back, forward);
    std::vector<float3> spread = pts;
    spread.push_back(float3(1e6f * R, 0, 0));
    spread.push_back(float3(0, -1e6f * R, 0));
    std::vector<std::string> wide = probe(spread);
    ASSERT_EQ(wide.size(), spread.size());
    // The far points' own rows: a distance of about 1e6 R.
    EXPECT_NEAR(std::stod(wide[pts.size()].substr(wide[pts.size()].find(',', wide[pts.size()].find(',', wide[pts.size()].find(',') + 1) + 1) + 1)),
                1e6 * R - R, 1e6 * R * 1e-5);
    wide.resize(pts.size());
    EXPECT_EQ(wide, forward);
}

TEST(ProbeCli, BadPointFilesNameTheFileAndWriteNothing)
{
    TempDir dir;
    const std::string head = test::sphere_scalp(dir);
    write_text(dir.file("bad.txt"), "1 2 3\n4 5\n");
    write_text(dir.file("bad.npy"), "not an array");
    const struct {
        std::string input, message;
    } cases[] = {
        {dir.file("bad.txt"), dir.file("bad.txt") + ":2: expected three finite numbers 'x y z', got '4 5'"},
        {dir.file("bad.npy"), dir.file("bad.npy") + ": not a NumPy .npy file"},
        {dir.file("missing.txt"), dir.file("missing.txt") + ": cannot open"},
    };
    for (const auto& c : cases) {
        const auto r = run_groom({"probe", "--scalp", head, c.input, "-o", dir.file("o.csv")});
        EXPECT_NE(r.exit_code, 0);
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir.file("o.csv")));
    }
}

}  // namespace
}  // namespace groom
