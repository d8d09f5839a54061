// Shared helpers for the test suites: temporary folders, the real datasets beside the repository,
// and running the `groom` executable.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace groom::test {

/// A fresh, empty folder removed at destruction.
class TempDir {
public:
    TempDir();
    ~TempDir();
    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

/// `../shared/datasets` beside the repository, or empty when absent (a user's fresh clone).
std::filesystem::path shared_datasets();

/// Path of one real dataset file, or empty when ../shared is absent.
std::string shared_file(const std::string& relative);

struct RunResult {
    int exit_code = -1;
    std::string out, err;
};

/// Runs the groom executable with `args` (no shell), capturing stdout and stderr. A non-zero
/// `file_size_limit` (bytes) caps every file it writes (RLIMIT_FSIZE, SIGXFSZ ignored), so a write
/// past it fails part-way exactly as on a full disk.
RunResult run_groom(const std::vector<std::string>& args, const std::string& stdin_text = {}, uint64_t file_size_limit = 0);

/// How run_groom(args, options) starts the process, for tests of hostile environments.
struct RunOptions {
    std::string stdin_text;
    /// RLIMIT_FSIZE in bytes (0 = none). SIGXFSZ keeps the disposition below, as `ulimit -f` in a
    /// shell leaves it: groom must ignore it itself.
    uint64_t file_size_limit = 0;
    bool ignore_sigxfsz = false;
    uint64_t address_space_limit = 0;  ///< RLIMIT_AS in bytes (0 = none), as `ulimit -v`
    /// Run as this user and group id when the test runs as root (-1 = as the test), so that file
    /// permissions apply as they do to a normal user.
    int uid = -1, gid = -1;
    std::vector<std::pair<std::string, std::string>> env;  ///< set in the child before exec
};
RunResult run_groom(const std::vector<std::string>& args, const RunOptions& options);

/// Whole file as bytes (empty if missing).
std::string read_bytes(const std::string& path);
void write_text(const std::string& path, const std::string& text);

}  // namespace groom::test

/// Skips the current test, saying why, when the real datasets are absent.
#define GROOM_REQUIRE_SHARED(var, relative)                                                                   \
    const std::string var = ::groom::test::shared_file(relative);                                           \
    if (var.empty()) GTEST_SKIP() << "../shared/datasets/" << relative << " not found (real data is only beside " \
                                     "the repository in CI and developer checkouts, not in a user's clone)"
