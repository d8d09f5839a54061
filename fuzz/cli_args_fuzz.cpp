// libFuzzer target: the whole `groom` command line (cli::run) with arbitrary arguments, for every
// registered command: CLI11 parsing, our unknown-command/option suggestions, list and range parsing
// (parse_floats), and each op's params validate(). The input is the argument list, one per line.
//
// It runs in an empty private directory with no way out of it (arguments containing '/' are
// skipped), so every input file a command names is missing: commands parse and validate their
// options, then stop at reading the input, and no op runs on real data. Checked on every run:
//   - the exit code is 0, 1 or 2 (cli::run never lets an exception escape);
//   - a command that fails leaves no file behind (writes are atomic);
// and, as for every target, no crash, sanitizer report, hang or huge allocation.
#include "cli/command.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::filesystem::path sandbox;
std::ostringstream discard;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    sandbox = std::filesystem::temp_directory_path() / ("groom_cli_fuzz_" + std::to_string(::getpid()));
    std::filesystem::remove_all(sandbox);
    std::filesystem::create_directories(sandbox);
    std::filesystem::current_path(sandbox);  // scripts/fuzz.sh passes absolute corpus and artifact paths
    // "-" means stdin: make it empty rather than waiting on the terminal.
    const int null_fd = ::open("/dev/null", O_RDONLY);
    ::dup2(null_fd, 0);
    // Help, notes and error messages go nowhere (libFuzzer reports on stderr via stdio, not iostreams).
    std::cout.rdbuf(discard.rdbuf());
    std::cerr.rdbuf(discard.rdbuf());
    std::atexit([] {
        std::error_code ec;
        std::filesystem::remove_all(sandbox, ec);
    });
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    std::vector<std::string> args{"groom"};
    std::string cur;
    for (size_t i = 0; i <= size; ++i) {
        if (i == size || data[i] == '\n') {
            if (cur.find('/') == std::string::npos && cur.find('\0') == std::string::npos) args.push_back(cur);
            cur.clear();
            if (args.size() > 64) break;
        }
        else {
            cur += static_cast<char>(data[i]);
        }
    }
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    const int code = groom::cli::run(static_cast<int>(args.size()), argv.data());
    discard.str({});
    if (code != 0 && code != 1 && code != 2) __builtin_trap();

    bool left_something = false;
    for (const auto& entry : std::filesystem::directory_iterator(sandbox)) {
        left_something = true;
        std::filesystem::remove_all(entry.path());
    }
    if (code != 0 && left_something) __builtin_trap();  // a failed command must leave no (partial) file
    return 0;
}
