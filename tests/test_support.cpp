#include "test_support.h"

#include <fcntl.h>
#include <grp.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <fstream>
#include <random>
#include <sstream>

namespace groom::test {

TempDir::TempDir()
{
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("groom_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir()
{
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

std::filesystem::path shared_datasets()
{
    const std::filesystem::path p = std::filesystem::path(GROOM_SOURCE_DIR) / ".." / "shared" / "datasets";
    return std::filesystem::is_directory(p) ? std::filesystem::canonical(p) : std::filesystem::path();
}

std::string shared_file(const std::string& relative)
{
    const auto root = shared_datasets();
    if (root.empty()) return {};
    const auto p = root / relative;
    return std::filesystem::exists(p) ? p.string() : std::string();
}

std::string read_bytes(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

void write_text(const std::string& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

RunResult run_groom(const std::vector<std::string>& args, const std::string& stdin_text, uint64_t file_size_limit)
{
    RunOptions o;
    o.stdin_text = stdin_text;
    o.file_size_limit = file_size_limit;
    o.ignore_sigxfsz = true;
    return run_groom(args, o);
}

RunResult run_groom(const std::vector<std::string>& args, const RunOptions& options)
{
    TempDir dir;
    const std::string in = dir.file("stdin"), out = dir.file("stdout"), err = dir.file("stderr");
    write_text(in, options.stdin_text);
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int fi = ::open(in.c_str(), O_RDONLY), fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644),
                  fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(fi, 0);
        ::dup2(fo, 1);
        ::dup2(fe, 2);
        ::signal(SIGXFSZ, options.ignore_sigxfsz ? SIG_IGN : SIG_DFL);
        if (options.file_size_limit > 0) {
            // The limit applies to our capture files too: they are opened already, and stay small.
            const rlimit rl{rlim_t(options.file_size_limit), rlim_t(options.file_size_limit)};
            ::setrlimit(RLIMIT_FSIZE, &rl);
        }
        if (options.address_space_limit > 0) {
            const rlimit rl{rlim_t(options.address_space_limit), rlim_t(options.address_space_limit)};
            ::setrlimit(RLIMIT_AS, &rl);
        }
        for (const auto& [name, value] : options.env) ::setenv(name.c_str(), value.c_str(), 1);
        if (::geteuid() == 0 && options.uid >= 0) {
            if (::setgroups(0, nullptr) != 0 || ::setgid(gid_t(options.gid >= 0 ? options.gid : options.uid)) != 0 ||
                ::setuid(uid_t(options.uid)) != 0) {
                ::_exit(126);
            }
        }
        std::vector<std::string> all{GROOM_BINARY};
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (auto& a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = read_bytes(out);
    r.err = read_bytes(err);
    return r;
}

}  // namespace groom::test
