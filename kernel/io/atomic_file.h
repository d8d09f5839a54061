// Atomic output: write to a temporary file beside the target, rename over it when complete. If
// anything throws before commit(), the temporary is removed and the target is left untouched. A
// symbolic link's target is what is replaced (the link stays); a device, FIFO or socket
// (`-o /dev/null`) is written into directly, without a temporary.
// A command with several outputs writes them through one OutputBatch: every output is written and
// checked in its temporary first, and only then are all renamed into place, so a failed second
// output never leaves a new first one beside an old second one.
// Temporaries in flight are listed where a signal handler can find them (remove_temporaries_on_signal),
// so SIGINT or SIGTERM part-way through a write leaves no `*.tmp.PID.N` behind either.
#pragma once

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace groom {

class AtomicOutput {
public:
    /// Opens a temporary beside `path` (or stdout when path is "-"). Throws IoError.
    explicit AtomicOutput(std::string path, bool binary = true);
    ~AtomicOutput();
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;

    std::ostream& stream();
    /// Flushes and closes the temporary and checks that every byte reached it; the target is not
    /// touched yet. Throws IoError naming the target and the system's reason (EFBIG, ENOSPC ...).
    void finish();
    /// finish(), then renames the temporary onto the target. Throws IoError.
    void commit();
    const std::string& path() const { return path_; }

private:
    struct File;  ///< the temporary: a file descriptor behind a stream that keeps the failing write's errno
    std::string path_, temp_;
    std::string target_;  ///< where a symbolic link `path_` points: what is replaced, the link kept
    std::unique_ptr<File> file_;
    int slot_ = -1;  ///< in the registry of temporaries, or -1
    bool finished_ = false;
    bool committed_ = false;
    bool to_stdout_ = false;
    bool in_place_ = false;  ///< a device, FIFO or socket: written into directly, no temporary
};

/// Every output of one command, committed together: open() each, write it, then commit() checks all
/// of them complete before renaming any. Destroyed uncommitted, it removes every temporary. (The
/// renames themselves are separate system calls: if one of those fails, which needs the folder to
/// change under us, the outputs renamed before it stay.)
class OutputBatch {
public:
    OutputBatch() = default;
    OutputBatch(const OutputBatch&) = delete;
    OutputBatch& operator=(const OutputBatch&) = delete;

    /// A stream into `path`'s temporary. Throws IoError.
    std::ostream& open(const std::string& path, bool binary = true);
    /// Work that stands for an output that is not a file (an in-memory "file"): run at commit().
    void defer(std::function<void()> action);
    /// Finishes every file (throws IoError on the first that failed; nothing is renamed then),
    /// renames them all into place, then runs the deferred actions.
    void commit();

private:
    std::vector<std::unique_ptr<AtomicOutput>> files_;
    std::vector<std::function<void()>> deferred_;
};

/// True when `path` is a device, FIFO or socket: an output AtomicOutput writes into as it is, which
/// needs no extension to be written (`-o /dev/null` writes what `-o -` would).
bool written_in_place(const std::string& path);

/// Removes every temporary still in flight, with unlink() only: async-signal-safe, for a signal
/// handler (cli/main.cpp installs it for SIGINT, SIGTERM and SIGHUP).
void remove_temporaries_on_signal() noexcept;

}  // namespace groom
