// Writes the fuzzers' seed corpus: small valid files of every format, made with groom's own writers
// where one exists (so the seeds follow the writers as they change) plus hand-written files for the
// reader paths our writers never produce (cubic USD, indexed primvars, ASCII STL, OFF...), and one
// seed command line per option of every registered `groom` command, with a libFuzzer dictionary of
// the option names. Usage: make_fuzz_corpus OUT_DIR   (creates OUT_DIR/<target>/ and OUT_DIR/cli_args.dict)
#include "cli/command.h"
#include "kernel/error.h"
#include "kernel/io/formats.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>

namespace fs = std::filesystem;
using namespace groom;

namespace {

fs::path out_dir;
int written = 0;

void seed(const std::string& target, const std::string& name, const std::string& bytes)
{
    fs::create_directories(out_dir / target);
    std::ofstream(out_dir / target / name, std::ios::binary) << bytes;
    ++written;
}

/// A writer that is not implemented yet (or refuses the sample) just gives no seed.
template <class F> void seed_from(const std::string& target, const std::string& name, F&& make)
{
    try {
        seed(target, name, make());
    }
    catch (const Error& e) {
        std::cerr << "make_fuzz_corpus: no " << target << "/" << name << " seed: " << e.what() << "\n";
    }
}

/// Three curves (4, 2 and 5 points) with a width per point, an id and a colour per curve and a
/// detail string; and one bare two-point curve.
std::vector<CurveSet> sample_curves()
{
    const int64_t counts[] = {4, 2, 5};
    CurveSet a = CurveSet::from_counts(counts);
    auto P = a.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = {float(i % 3) * 0.5f, float(i) * 1.25f, -float(i) / 3.0f};
    auto w = a.add<float>(Domain::Point, "width");
    for (size_t i = 0; i < w.size(); ++i) w[i] = 0.01f * float(i + 1);
    auto id = a.add<int32_t>(Domain::Curve, "id");
    for (size_t c = 0; c < id.size(); ++c) id[c] = int32_t(c * 7 + 1);
    auto cd = a.add<float3>(Domain::Curve, "Cd");
    for (size_t c = 0; c < cd.size(); ++c) cd[c] = {0.1f * float(c), 0.5f, 1.0f};
    a.set_detail_string("hair_type", "4a");

    const int64_t one[] = {2};
    CurveSet b = CurveSet::from_counts(one);
    b.positions_for_write()[1] = {0, 10, 0};
    return {a, b};
}

PolygonSoup tetrahedron()
{
    PolygonSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (auto f : {std::vector<int32_t>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}) s.add_face(f);
    return s;
}

PolygonSoup quad_and_triangle()
{
    PolygonSoup s;
    s.points = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 3}};
    for (auto f : {std::vector<int32_t>{0, 1, 2, 3}, {0, 1, 4}}) s.add_face(f);
    return s;
}

std::string binary_stl(const PolygonSoup& s)
{
    std::string out(80, '\0');
    std::memcpy(out.data(), "groom fuzz seed", 15);
    const uint32_t n = static_cast<uint32_t>(s.num_faces());
    out.append(reinterpret_cast<const char*>(&n), 4);
    for (size_t f = 0; f < s.num_faces(); ++f) {
        const float normal[3] = {0, 0, 0};
        out.append(reinterpret_cast<const char*>(normal), 12);
        for (int32_t i : s.face(f)) out.append(reinterpret_cast<const char*>(&s.points[i]), 12);
        out.append(2, '\0');
    }
    return out;
}

void curve_seeds()
{
    const std::vector<CurveSet> samples = sample_curves();
    for (size_t k = 0; k < samples.size(); ++k) {
        const std::string n = "writer_" + std::to_string(k);
        seed_from("usda", n + ".usda", [&] { return io::write_usda(samples[k]); });
        seed_from("obj_curves", n + ".obj", [&] { return io::write_obj_curves(samples[k]); });
        seed_from("ply_curves", n + "_binary.ply", [&] { return io::write_ply_curves(samples[k], PlyEncoding::Binary); });
        seed_from("ply_curves", n + "_ascii.ply", [&] { return io::write_ply_curves(samples[k], PlyEncoding::Ascii); });
        seed_from("hair", n + ".hair", [&] { return io::write_hair(samples[k]); });
    }
    // Reader paths the writer never takes: cubic bases, pinned wrap, varying and indexed primvars,
    // timeSamples, nested prims, layer and property metadata, comments.
    seed("usda", "cubic_catmullrom.usda", R"(#usda 1.0
(
    defaultPrim = "root"
    metersPerUnit = 0.01
)
def Xform "root" (kind = "component")
{
    double3 xformOp:translate = (0, 1, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
    def BasisCurves "hair"
    {
        uniform token type = "cubic"
        uniform token basis = "catmullRom"
        int[] curveVertexCounts = [4, 5]
        point3f[] points = [(0,0,0), (0,1,0), (0,2,0), (0,3,0), (1,0,0), (1,1,0.5), (1,2,1), (1,3,1.5), (1,4,2)]
        float[] widths = [0.1, 0.05, 0.2] (interpolation = "varying")
        int[] primvars:strand = [3, 9] (interpolation = "uniform")
        color3f[] primvars:displayColor = [(1, 0, 0)] (interpolation = "constant")
        string primvars:hair_type = "3b"
        // a comment
        /* and a block comment */
    }
}
)");
    seed("usda", "bspline_pinned_indexed.usda", R"(#usda 1.0
def BasisCurves "c"
{
    uniform token type = "cubic"
    uniform token basis = "bspline"
    uniform token wrap = "pinned"
    int[] curveVertexCounts = [3]
    point3f[] points.timeSamples = { 1: [(0,0,0), (1,1,1), (2,0,2)], 0: [(0,0,0), (1,2,1), (2,0,2)] }
    float[] primvars:u = [0.5, 1.5] (interpolation = "vertex")
    int[] primvars:u:indices = [0, 1, 1]
    rel material:binding = </Looks/m>
}
over "Looks" { def Material "m" {} }
)");
    seed("usda", "linear_widths_constant.usda",
         "#usda 1.0\ndef BasisCurves \"l\" { uniform token type = \"linear\"\n int[] curveVertexCounts = [2, 3]\n"
         " point3f[] points = [(0,0,0),(0,1,0),(1,0,0),(1,1,0),(1,2,0)]\n float widths = 0.02 (interpolation = \"constant\")\n}\n");
    seed("obj_curves", "relative_indices.obj", "# comment\nv 0 0 0\nv 0 1 0\nv 0 2 0\nl -3 -2 -1\no strands\nv 1 0 0\nv 1 1 0\nl 4 5\n");
}

void mesh_seeds()
{
    for (const auto& sample : {std::pair{"tetrahedron", tetrahedron()}, std::pair{"quad_triangle", quad_and_triangle()}}) {
        const std::string name = sample.first, n = "writer_" + name;
        const PolygonSoup& soup = sample.second;
        seed_from("obj_mesh", n + ".obj", [&] { return io::write_obj_mesh(soup); });
        seed_from("ply_mesh", n + ".ply", [&] { return io::write_ply_mesh(soup); });
        seed("stl", name + "_binary.stl", binary_stl(soup));
    }
    seed("obj_mesh", "slashes.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf -3//1 -2//1 -1//1\n");
    seed("ply_mesh", "ascii.ply",
         "ply\nformat ascii 1.0\ncomment fuzz seed\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
    seed("off", "tetrahedron.off", "OFF\n# tetrahedron\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
    seed("off", "quad.off", "OFF 4 1 0\n0 0 0 1 0 0 1 1 0 0 1 0\n4 0 1 2 3\n");
    seed("stl", "ascii.stl",
         "solid fuzz\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
         "    endloop\n  endfacet\nendsolid fuzz\n");
}

/// Captures what cli::run prints on stdout for `args` (its --help text).
std::string help_of(std::vector<std::string> args)
{
    args.insert(args.begin(), "groom");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    std::ostringstream captured;
    std::streambuf* old = std::cout.rdbuf(captured.rdbuf());
    groom::cli::run(static_cast<int>(argv.size()), argv.data());
    std::cout.rdbuf(old);
    return captured.str();
}

/// Command lines: for each command, the bare required form and one line per option with a
/// plausible value (the default CLI11 shows, else a number), plus a dictionary of every option.
void cli_seeds()
{
    const std::string top = help_of({"--help"});
    std::vector<std::string> commands;
    const size_t sub = top.find("Subcommands:");
    if (sub != std::string::npos) {
        std::istringstream lines(top.substr(sub));
        std::string line;
        std::getline(lines, line);
        const std::regex row(R"(^\s+([a-z][a-z0-9_-]*)\s)");
        std::smatch m;
        while (std::getline(lines, line))
            if (std::regex_search(line, m, row)) commands.push_back(m[1]);
    }
    std::set<std::string> dict{"-o", "--help", "--threads", "--force", "-q", "-v", "-", "0", "-1", "1e30", "nan", "inf", ",", "1,2",
                               "0.5,0.25", "1,2,3", "2147483648", "9223372036854775808"};
    const std::regex option(R"(^\s+(?:-\w,)?(--[a-z][a-z0-9-]*)(?:\s+[A-Z:]+)?(?:=(\S+))?)");
    for (const std::string& cmd : commands) {
        dict.insert(cmd);
        const std::string base = cmd + "\nin.obj\n-o\nout.usda\n";
        seed("cli_args", cmd + "_bare", base);
        std::istringstream lines(help_of({cmd, "--help"}));
        std::string line;
        std::smatch m;
        while (std::getline(lines, line)) {
            if (!std::regex_search(line, m, option)) continue;
            const std::string name = m[1], value = m[2].matched ? std::string(m[2]) : "1";
            if (name == "--help" || name == "--output") continue;
            dict.insert(name);
            seed("cli_args", cmd + "_" + name.substr(2), base + name + "\n" + value + "\n");
        }
    }
    seed("cli_args", "unknown_command", "curll\nin.obj\n");
    seed("cli_args", "version", "--version\n");
    std::ofstream d(out_dir / "cli_args.dict");
    for (const std::string& w : dict) d << '"' << w << "\"\n";

    seed("parse_floats", "triple", std::string(1, char(3 | (0 << 2))) + "1,2.5,-3e-2");
    seed("parse_floats", "range", std::string(1, char(1 | (1 << 2))) + " 0.1 , 0.2");
    seed("parse_floats", "bad", std::string(1, char(1)) + "1,,x");
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::cerr << "usage: make_fuzz_corpus OUT_DIR\n";
        return 2;
    }
    out_dir = argv[1];
    fs::create_directories(out_dir);
    curve_seeds();
    mesh_seeds();
    cli_seeds();
    std::cout << "make_fuzz_corpus: " << written << " seed files in " << out_dir.string() << "\n";
    return 0;
}
