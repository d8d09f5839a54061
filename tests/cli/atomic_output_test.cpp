// Nothing lost on bad input or a failed write (issue 9): for every command that writes a file,
//   - an error before or during the write leaves the previous output byte-for-byte untouched and
//     no temporary file behind (writes go to a temporary and are renamed into place, atomic_file.h);
//   - `-o` naming one of the command's inputs (by any path spelling) is refused unless --force.
// "During the write" is real: the command runs with a file-size limit (RLIMIT_FSIZE) below its
// output's size, so its write fails part-way exactly as on a full disk.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"


#include <sys/stat.h>

#include <filesystem>
#include <thread>

using namespace groom;
using groom::test::run_groom;
namespace fs = std::filesystem;

namespace {

const std::string kPrevious = "previous output: must survive every failed run\n";

/// 60 straight guides of 8 points as .usda.
std::string write_guides(const test::TempDir& dir, const std::string& name = "guides.usda")
{
    std::vector<int64_t> counts(60, 8);
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = {float(i / 8) * 0.5f, float(i % 8), 0.25f * float(i / 8 % 3)};
    const std::string path = dir.file(name);
    write_curves(cs, path);
    return path;
}

/// Files in `dir` whose name contains ".tmp" (AtomicOutput's and write_scalp's temporaries).
std::vector<std::string> temporaries(const test::TempDir& dir)
{
    std::vector<std::string> t;
    for (const auto& e : fs::directory_iterator(dir.path()))
        if (e.path().filename().string().find(".tmp") != std::string::npos) t.push_back(e.path().filename().string());
    return t;
}

struct Case {
    const char* command;
    const char* output_ext;
    /// "{in}" (curve input), "{mesh}" (a sphere mesh), "{vdb}" (its level set) and "{out}" are replaced.
    std::vector<std::string> args;
    bool has_input;  ///< reads "{in}"
};

/// Every command that writes a file; a command joins when it lands on main.
std::vector<Case> cases()
{
    return {
        {"convert", "hair", {"convert", "{in}", "-o", "{out}"}, true},
        {"resample", "usda", {"resample", "{in}", "-o", "{out}", "--count", "20"}, true},
        {"select", "usda", {"select", "{in}", "-o", "{out}", "--ids", "0-1"}, true},
        {"transform", "usda", {"transform", "{in}", "-o", "{out}", "--scale", "2"}, true},
        {"curl", "usda", {"curl", "{in}", "-o", "{out}", "--seed", "3"}, true},
        {"head", "obj", {"head", "-o", "{out}", "--resolution", "48"}, false},
        {"render", "png", {"render", "{in}", "-o", "{out}", "--size", "256x256"}, true},
        {"scalp", "vdb", {"scalp", "{mesh}", "-o", "{out}"}, false},
        {"project", "usda", {"project", "{in}", "--scalp", "{vdb}", "-o", "{out}", "--mode", "root"}, true},
        {"cull", "usda", {"cull", "{in}", "--scalp", "{vdb}", "-o", "{out}", "--mode", "push"}, true},
    };
}

/// The sphere scalp every case may use, made once per test binary.
struct Scalp {
    test::TempDir dir;
    std::string mesh = dir.file("sphere.obj"), vdb = dir.file("sphere.vdb");
    Scalp()
    {
        write_mesh(icosphere(float3(0, 0, 0), 10.0f, 3), mesh);
        const auto r = run_groom({"scalp", mesh, "-o", vdb});
        EXPECT_EQ(r.exit_code, 0) << r.err;
    }
};
const Scalp& scalp()
{
    static const Scalp s;
    return s;
}

std::vector<std::string> expand(const Case& c, const std::string& in, const std::string& out)
{
    std::vector<std::string> r;
    for (const std::string& a : c.args) {
        r.push_back(a == "{in}" ? in : a == "{out}" ? out : a == "{mesh}" ? scalp().mesh : a == "{vdb}" ? scalp().vdb : a);
    }
    return r;
}

}  // namespace

TEST(AtomicOutput, AFailedWriteLeavesThePreviousOutputUntouched)
{
    test::TempDir dir;
    const std::string guides = write_guides(dir);
    for (const Case& c : cases()) {
        const std::string out = dir.file(std::string("out_") + c.command + "." + c.output_ext);
        // First the real size of the output, so the limit below is sure to cut the write part-way.
        const auto ok = run_groom(expand(c, guides, out));
        ASSERT_EQ(ok.exit_code, 0) << c.command << ": " << ok.err;
        const auto full_size = fs::file_size(out);
        ASSERT_GT(full_size, 2 * kPrevious.size()) << c.command;

        test::write_text(out, kPrevious);
        const auto failed = run_groom(expand(c, guides, out), {}, full_size / 2);
        EXPECT_EQ(failed.exit_code, 1) << c.command << ": " << failed.err;
        EXPECT_NE(failed.err.find("groom: error:"), std::string::npos) << c.command << ": " << failed.err;
        EXPECT_TRUE(test::read_bytes(out) == kPrevious) << c.command << ": the previous output was changed by a failed write";
        EXPECT_TRUE(temporaries(dir).empty()) << c.command << " left " << temporaries(dir).front();
    }
}

TEST(AtomicOutput, BadInputLeavesThePreviousOutputUntouched)
{
    test::TempDir dir;
    // A .usda that starts well and breaks on its last line: the reader has done most of its work.
    const std::string good = test::read_bytes(write_guides(dir));
    const std::string bad = dir.file("broken.usda");
    test::write_text(bad, good.substr(0, good.rfind('}')) + "    float[] primvars:oops = [1, 2,\n");
    for (const Case& c : cases()) {
        if (!c.has_input) continue;
        const std::string out = dir.file(std::string("out_") + c.command + "." + c.output_ext);
        test::write_text(out, kPrevious);
        const auto r = run_groom(expand(c, bad, out));
        EXPECT_EQ(r.exit_code, 1) << c.command << ": " << r.err;
        EXPECT_NE(r.err.find("broken.usda:"), std::string::npos) << c.command << ": the message should name the file: " << r.err;
        EXPECT_EQ(test::read_bytes(out), kPrevious) << c.command;
        EXPECT_TRUE(temporaries(dir).empty()) << c.command;
    }
}

TEST(AtomicOutput, OutputIntoAMissingFolderCreatesNothing)
{
    test::TempDir dir;
    const std::string guides = write_guides(dir);
    for (const Case& c : cases()) {
        const std::string out = dir.file(std::string("missing/out.") + c.output_ext);
        const auto r = run_groom(expand(c, guides, out));
        // Refused before any work, as a parameter (exit 2), naming the folder.
        EXPECT_EQ(r.exit_code, 2) << c.command << ": " << r.err;
        EXPECT_NE(r.err.find("missing/out." + std::string(c.output_ext) + ": the folder " + dir.file("missing") + " does not exist"), std::string::npos)
            << c.command << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir.file("missing"))) << c.command;
    }
}

TEST(AtomicOutput, OutputOntoAnInputIsRefusedUnlessForced)
{
    for (const Case& c : cases()) {
        if (!c.has_input) continue;
        test::TempDir dir;
        const std::string in = write_guides(dir, "in.usda");
        const std::string before = test::read_bytes(in);
        // -o names the input by another spelling: "./" for a .usda output, or a link with the
        // output's extension for other formats. The check compares files, not strings.
        const bool same_format = std::string(c.output_ext) == "usda";
        const std::string alias = same_format ? (dir.path() / "." / "in.usda").string() : dir.file(std::string("link.") + c.output_ext);
        if (!same_format) fs::create_symlink(in, alias);
        const auto r = run_groom(expand(c, in, alias));
        EXPECT_EQ(r.exit_code, 2) << c.command << ": " << r.err;
        EXPECT_NE(r.err.find("--force"), std::string::npos) << c.command << ": " << r.err;
        EXPECT_EQ(test::read_bytes(in), before) << c.command << ": the input was changed";
        if (same_format) {
            auto forced_args = expand(c, in, alias);
            forced_args.push_back("--force");
            const auto forced = run_groom(forced_args);
            EXPECT_EQ(forced.exit_code, 0) << c.command << ": " << forced.err;
            EXPECT_NE(test::read_bytes(in), before) << c.command << ": --force should have written over the input";
        }
    }
}

// A FIFO (or a device: `-o /dev/null`) given as the output is written into, not replaced by a
// regular file (as root, `-o /dev/null` had replaced /dev/null itself: a trial); a symbolic link's
// target is written and the link kept (it had been replaced by a file, its target left as it was).
TEST(AtomicOutput, SpecialFilesAreWrittenIntoAndLinksFollowed)
{
    for (const Case& c : cases()) {
        test::TempDir dir;
        const std::string in = write_guides(dir, "in.usda");
        // Into a regular file first, for the bytes the others must hold.
        const std::string plain = dir.file(std::string("plain.") + c.output_ext);
        ASSERT_EQ(run_groom(expand(c, in, plain)).exit_code, 0) << c.command;
        const std::string want = test::read_bytes(plain);
        // A symbolic link to an existing file of another folder: the target is replaced, the link stays.
        fs::create_directory(dir.path() / "elsewhere");
        const std::string target = (dir.path() / "elsewhere" / (std::string("t.") + c.output_ext)).string();
        test::write_text(target, kPrevious);
        const std::string link = dir.file(std::string("link.") + c.output_ext);
        fs::create_symlink(target, link);
        auto r = run_groom(expand(c, in, link));
        EXPECT_EQ(r.exit_code, 0) << c.command << ": " << r.err;
        EXPECT_TRUE(fs::is_symlink(link)) << c.command << ": the link was replaced";
        EXPECT_EQ(test::read_bytes(target), want) << c.command;
        EXPECT_TRUE(temporaries(dir).empty()) << c.command;
        // A link whose target does not exist yet (the first run): the target is made, the link kept.
        const std::string later = (dir.path() / "elsewhere" / (std::string("later.") + c.output_ext)).string();
        const std::string dangling = dir.file(std::string("dangling.") + c.output_ext);
        fs::create_symlink(fs::path("elsewhere") / (std::string("later.") + c.output_ext), dangling);
        r = run_groom(expand(c, in, dangling));
        EXPECT_EQ(r.exit_code, 0) << c.command << ": " << r.err;
        EXPECT_TRUE(fs::is_symlink(dangling)) << c.command << ": the dangling link was replaced";
        EXPECT_EQ(test::read_bytes(later), want) << c.command;
        // A FIFO: a reader gets the bytes; the FIFO is still one afterwards. .hair is written a
        // block at a time at its places, which a FIFO cannot take: refused, saying so.
        const std::string fifo = dir.file(std::string("fifo.") + c.output_ext);
        ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
        std::string got;
        std::thread reader([&] { got = test::read_bytes(fifo); });
        r = run_groom(expand(c, in, fifo));
        reader.join();
        EXPECT_TRUE(fs::is_fifo(fifo)) << c.command << ": the FIFO was replaced";
        if (c.output_ext == std::string("hair")) {
            EXPECT_EQ(r.exit_code, 1) << c.command << ": " << r.err;
            EXPECT_NE(r.err.find("cannot seek: this format is written at places, so write it to a file"), std::string::npos) << r.err;
        } else {
            EXPECT_EQ(r.exit_code, 0) << c.command << ": " << r.err;
            EXPECT_EQ(got.size(), want.size()) << c.command;
        }
        EXPECT_TRUE(temporaries(dir).empty()) << c.command;
    }
}

// A device or FIFO needs no extension: `-o /dev/null` runs every command (it had been refused as
// "unknown curve format '.'", a trial), and a FIFO named without one receives what `-o -` writes.
// A regular file without one is refused, saying there is no extension (not "format '.'").
TEST(AtomicOutput, DevicesNeedNoExtension)
{
    test::TempDir dir;
    const std::string in = write_guides(dir, "in.usda");
    for (const Case& c : cases()) {
        const auto r = run_groom(expand(c, in, "/dev/null"));
        EXPECT_EQ(r.exit_code, 0) << c.command << ": " << r.err;
    }
    const std::string fifo = dir.file("fifo");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    std::string got;
    std::thread reader([&] { got = test::read_bytes(fifo); });
    const auto r = run_groom({"convert", in, "-o", fifo});
    reader.join();
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto out = run_groom({"convert", in, "-o", "-"});
    ASSERT_EQ(out.exit_code, 0) << out.err;
    EXPECT_EQ(got, out.out);
    const auto plain = run_groom({"convert", in, "-o", dir.file("noext")});
    EXPECT_EQ(plain.exit_code, 2);
    EXPECT_NE(plain.err.find("noext: no extension to tell the curve format by (expected .usda, .obj, .ply, .hair)"), std::string::npos) << plain.err;
}

// `-o` naming the --scalp mesh is refused as for any input (curl had overwritten its scalp with curves).
TEST(AtomicOutput, OutputOntoTheScalpMeshIsRefused)
{
    test::TempDir dir;
    const std::string in = write_guides(dir);
    const std::string mesh = dir.file("head.obj");
    write_mesh(icosphere(float3(0, 0, 0), 10.0f, 2), mesh);
    const std::string before = test::read_bytes(mesh);
    for (const std::string command : {"curl", "project", "cull", "braid", "generate"}) {
        std::vector<std::string> args = {command, in, "--scalp", mesh, "-o", mesh};
        if (command == "generate") args.insert(args.end(), {"--count", "10"});
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 2) << command << ": " << r.err;
        EXPECT_NE(r.err.find("is also an input file"), std::string::npos) << command << ": " << r.err;
        EXPECT_EQ(test::read_bytes(mesh), before) << command << ": the scalp was overwritten";
    }
}
