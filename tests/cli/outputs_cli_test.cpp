// Outputs under hostile conditions (issue 20): every output of a command lands together or not at
// all, two outputs naming one file are refused, a read-only output needs --force, and neither
// `ulimit -f` (SIGXFSZ) nor SIGINT/SIGTERM part-way through a write leaves a temporary behind.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

using namespace groom;
using groom::test::run_groom;
namespace fs = std::filesystem;

namespace {

const std::string kPrevious = "previous output: must survive every failed run\n";

/// `n` straight guides of `points` points as .usda.
std::string write_guides(const test::TempDir& dir, int n = 60, int points = 8, const std::string& name = "guides.usda")
{
    std::vector<int64_t> counts(size_t(n), points);
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = {float(i / points) * 0.5f, float(i % points), 0.25f * float(i / points % 3)};
    const std::string path = dir.file(name);
    write_curves(cs, path);
    return path;
}

/// Files in `dir` whose name contains ".tmp" (AtomicOutput's temporaries).
std::vector<std::string> temporaries(const test::TempDir& dir)
{
    std::vector<std::string> t;
    for (const auto& e : fs::directory_iterator(dir.path()))
        if (e.path().filename().string().find(".tmp") != std::string::npos) t.push_back(e.path().filename().string());
    return t;
}

std::string sphere_mesh(const test::TempDir& dir)
{
    const std::string path = dir.file("sphere.obj");
    write_mesh(icosphere(float3(0, 0, 0), 10.0f, 3), path);
    return path;
}

}  // namespace

TEST(Outputs, TwoOutputsNamingOneFileAreRefusedUpFront)
{
    test::TempDir dir;
    const std::string mesh = sphere_mesh(dir);
    const std::string guides = write_guides(dir);
    const std::string t = dir.file("t.usda"), same_by_another_name = (dir.path() / "." / "t.usda").string();
    // Each pair named by one string and, for a file that does not exist yet, by another spelling.
    const std::vector<std::vector<std::string>> cases = {
        {"cornrow-guides", "--scalp", mesh, "-o", t, "--tails-out", t},
        {"cornrow-guides", "--scalp", mesh, "-o", t, "--tails-out", same_by_another_name},
        {"scalp", mesh, "-o", dir.file("s.vdb"), "--report", dir.file("s.vdb")},
        {"puff", "--scalp", mesh, "-o", t, "--guides-out", same_by_another_name, "--center", "0,10,0", "--radius", "3",
         "--sphere-center", "0,16,0", "--sphere-radius", "4", "--hairs", "5"},
        {"partition", guides, "--scalp", mesh, "-o", t, "--write-adjacent", same_by_another_name},
        {"sections", "--scalp", mesh, "-o", dir.file("g.usda"), "--partings-out", t, "--roots-out", same_by_another_name},
    };
    for (const auto& args : cases) {
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
        EXPECT_NE(r.err.find("name the same file"), std::string::npos) << args[0] << ": " << r.err;
        EXPECT_FALSE(fs::exists(t)) << args[0];
        EXPECT_FALSE(fs::exists(dir.file("s.vdb"))) << args[0];
        // --force allows writing over an input, never one output over another.
        auto forced = args;
        forced.push_back("--force");
        EXPECT_EQ(run_groom(forced).exit_code, 2) << args[0];
    }
}

TEST(Outputs, AFailedSecondOutputLeavesTheFirstUntouched)
{
    test::TempDir dir;
    const std::string mesh = sphere_mesh(dir);
    const std::string out = dir.file("out.usda"), vdb = dir.file("out.vdb");
    test::write_text(out, kPrevious);
    test::write_text(vdb, kPrevious);
    // The second output goes into a folder that does not exist, or is a folder: refused before any
    // work (exit 2, a parameter error). A folder had been found only at the rename, after the first
    // output had replaced the user's file (a trial).
    fs::create_directory(dir.file("folder.usda"));
    const std::vector<std::vector<std::string>> cases = {
        {"cornrow-guides", "--scalp", mesh, "-o", out, "--tails-out", dir.file("folder.usda")},
        {"sections", "--scalp", mesh, "-o", out, "--roots-out", dir.file("folder.usda")},
        {"cornrow-guides", "--scalp", mesh, "-o", out, "--tails-out", dir.file("missing/tails.usda")},
        {"scalp", mesh, "-o", vdb, "--report", dir.file("missing/report.json")},
        {"puff", "--scalp", mesh, "-o", out, "--guides-out", dir.file("missing/guides.usda"), "--center", "0,10,0", "--radius", "3",
         "--sphere-center", "0,16,0", "--sphere-radius", "4", "--hairs", "5"},
    };
    for (const auto& args : cases) {
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
        const bool folder = args.back() == dir.file("folder.usda") || args[args.size() - 2] == dir.file("folder.usda");
        EXPECT_NE(r.err.find(folder ? "folder.usda is a folder; expected a file to write" : "missing does not exist; create it first"), std::string::npos)
            << args[0] << ": the message should name the output: " << r.err;
        EXPECT_EQ(test::read_bytes(out), kPrevious) << args[0] << ": the first output was replaced although the second failed";
        EXPECT_EQ(test::read_bytes(vdb), kPrevious) << args[0];
        EXPECT_TRUE(temporaries(dir).empty()) << args[0] << " left " << temporaries(dir).front();
    }
    // The same commands with both outputs possible write both.
    const auto ok = run_groom({"cornrow-guides", "--scalp", mesh, "-o", out, "--tails-out", dir.file("tails.usda")});
    ASSERT_EQ(ok.exit_code, 0) << ok.err;
    EXPECT_EQ(read_curves(out).num_curves(), read_curves(dir.file("tails.usda")).num_curves());
}

TEST(Outputs, AReadOnlyOutputNeedsForce)
{
    test::TempDir dir;
    // As a normal user: root may write any file, so the test drops to `nobody` when run as root.
    fs::permissions(dir.path(), fs::perms::all);
    const std::string in = write_guides(dir);
    const std::string out = dir.file("kept.usda");
    test::write_text(out, kPrevious);
    fs::permissions(out, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
    test::RunOptions as_user;
    as_user.uid = as_user.gid = 65534;
    const auto r = run_groom({"resample", in, "-o", out, "--count", "4"}, as_user);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("read-only"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
    EXPECT_EQ(test::read_bytes(out), kPrevious);

    const auto forced = run_groom({"resample", in, "-o", out, "--count", "4", "--force"}, as_user);
    EXPECT_EQ(forced.exit_code, 0) << forced.err;
    EXPECT_EQ(read_curves(out).num_points(), 60u * 4u);
}

// Whoever runs it: root may write any file (render farms and containers run as root), but a file
// whose mode says read-only is still one the user meant to keep. Replaced with --force, an output
// keeps its permissions, as does any output that is replaced.
TEST(Outputs, AReadOnlyOutputNeedsForceEvenForRootAndKeepsItsMode)
{
    test::TempDir dir;
    const std::string in = write_guides(dir);
    const std::string out = dir.file("kept.usda");
    test::write_text(out, kPrevious);
    const auto read_only = fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read;
    fs::permissions(out, read_only);
    const auto r = run_groom({"resample", in, "-o", out, "--count", "4"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("read-only"), std::string::npos) << r.err;
    EXPECT_EQ(test::read_bytes(out), kPrevious);
    ASSERT_EQ(run_groom({"resample", in, "-o", out, "--count", "4", "--force"}).exit_code, 0);
    EXPECT_EQ(read_curves(out).num_points(), 60u * 4u);
    EXPECT_EQ(fs::status(out).permissions(), read_only);

    const std::string shared = dir.file("shared.usda");
    test::write_text(shared, kPrevious);
    const auto group_write = fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::group_write;
    fs::permissions(shared, group_write);
    ASSERT_EQ(run_groom({"resample", in, "-o", shared, "--count", "4"}).exit_code, 0);
    EXPECT_EQ(fs::status(shared).permissions(), group_write);
}

TEST(Outputs, FileSizeLimitIsAnErrorNotASignal)
{
    test::TempDir dir;
    const std::string in = write_guides(dir);
    const std::string out = dir.file("out.usda");
    test::write_text(out, kPrevious);
    // As `ulimit -f` leaves a process: the limit, and SIGXFSZ at its default action (terminate).
    test::RunOptions limited;
    limited.file_size_limit = 4096;
    limited.ignore_sigxfsz = false;
    const auto r = run_groom({"resample", in, "-o", out, "--count", "200"}, limited);
    EXPECT_EQ(r.exit_code, 1) << "killed by a signal? exit " << r.exit_code << ": " << r.err;
    EXPECT_NE(r.err.find("groom: error: " + out + ": write failed (File too large)"), std::string::npos) << r.err;
    EXPECT_EQ(test::read_bytes(out), kPrevious);
    EXPECT_TRUE(temporaries(dir).empty()) << temporaries(dir).front();
}

TEST(Outputs, SignalDuringAWriteLeavesNoTemporary)
{
    for (const int sig : {SIGINT, SIGTERM}) {
        test::TempDir dir;
        const std::string in = write_guides(dir, 200, 8);
        const std::string out = dir.file("out.usda");
        test::write_text(out, kPrevious);
        // The write is held part-way on purpose: the child's first temporary (`out.usda.tmp.PID.0`)
        // is made a FIFO before groom starts, so groom blocks writing into it once the pipe is full
        // (the output is megabytes), with its temporary in place. Then the signal.
        int go[2];
        ASSERT_EQ(::pipe(go), 0);
        const pid_t pid = ::fork();
        if (pid == 0) {
            ::close(go[1]);
            char c = 0;
            if (::read(go[0], &c, 1) != 1) ::_exit(127);
            const int devnull = ::open("/dev/null", O_WRONLY);
            ::dup2(devnull, 1);
            ::dup2(devnull, 2);
            // Default dispositions, as from a shell (a test runner may ignore some).
            ::signal(SIGINT, SIG_DFL);
            ::signal(SIGTERM, SIG_DFL);
            ::execl(GROOM_BINARY, GROOM_BINARY, "resample", in.c_str(), "-o", out.c_str(), "--count", "2000", static_cast<char*>(nullptr));
            ::_exit(127);
        }
        ::close(go[0]);
        const std::string temp = out + ".tmp." + std::to_string(pid) + ".0";
        ASSERT_EQ(::mkfifo(temp.c_str(), 0600), 0);
        ASSERT_EQ(::write(go[1], "x", 1), 1);
        ::close(go[1]);
        const int fifo = ::open(temp.c_str(), O_RDONLY);  // returns once groom has opened it to write
        ASSERT_GE(fifo, 0);
        char buf[4096];
        ASSERT_EQ(::read(fifo, buf, sizeof buf), ssize_t(sizeof buf)) << "groom should be writing its output";
        ASSERT_EQ(::kill(pid, sig), 0);
        int status = 0;
        ::waitpid(pid, &status, 0);
        ::close(fifo);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "groom should die of signal " << sig << " (status " << status << ")";
        EXPECT_FALSE(fs::exists(fs::symlink_status(temp))) << "signal " << sig << " left the temporary " << temp;
        EXPECT_EQ(test::read_bytes(out), kPrevious);
        EXPECT_TRUE(temporaries(dir).empty()) << temporaries(dir).front();
    }
}
