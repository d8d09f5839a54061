#include "cli/command.h"
#include "kernel/io/atomic_file.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <new>

namespace {

/// Ctrl-C, `kill` or a closed terminal part-way through a write: remove the temporaries in flight
/// (unlink only: async-signal-safe), then die of the same signal, so the caller sees what happened.
extern "C" void remove_temporaries_and_die(int sig)
{
    groom::remove_temporaries_on_signal();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

std::terminate_handler g_default_terminate = nullptr;

/// A bad_alloc that reaches std::terminate: OpenVDB's trees allocate while they are destroyed, so
/// running out of memory inside meshToVolume throws again during unwinding, which no catch can
/// stop. Reported as the out-of-memory error it is (the option to change, the estimate), with the
/// temporaries removed, instead of "terminate called ... Aborted". Anything else aborts as before.
[[noreturn]] void on_terminate()
{
    bool out_of_memory = false;
    if (const std::exception_ptr e = std::current_exception()) {
        try {
            std::rethrow_exception(e);
        }
        catch (const std::bad_alloc&) {
            out_of_memory = true;
        }
        catch (...) {
        }
    }
    if (out_of_memory) {
        groom::remove_temporaries_on_signal();
        const std::string msg = "groom: error: " + groom::cli::out_of_memory_message() + "\n";
        [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, msg.data(), msg.size());
        ::_exit(1);
    }
    if (g_default_terminate) g_default_terminate();
    std::abort();
}

}  // namespace

int main(int argc, char** argv)
{
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
        // A signal the caller chose to ignore (nohup, a shell's background job) stays ignored.
        if (std::signal(sig, remove_temporaries_and_die) == SIG_IGN) std::signal(sig, SIG_IGN);
    }
    // Past `ulimit -f`, the default action of SIGXFSZ kills the process mid-write and leaves its
    // temporary behind; ignored, the write fails with EFBIG and the command reports it as an error
    // naming the file, like a full disk.
    std::signal(SIGXFSZ, SIG_IGN);
    g_default_terminate = std::set_terminate(on_terminate);
    return groom::cli::run(argc, argv);
}
