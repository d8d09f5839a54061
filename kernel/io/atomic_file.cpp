#include "kernel/io/atomic_file.h"

#include "kernel/error.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <streambuf>

namespace groom {

namespace {

std::string temp_name(const std::string& path)
{
    static std::atomic<unsigned> counter{0};
    // Same directory as the target so rename() is atomic (no cross-device move).
    return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

// The temporaries in flight, readable from a signal handler: fixed slots of fixed buffers (a handler
// may not allocate or take a lock), each claimed with a compare-and-swap. A slot's path is written
// before its state becomes kReady and the state is cleared before the slot is reused, so a handler
// only ever reads a whole path. A command has a handful of outputs; past kSlots they are simply not
// listed (the normal error path still removes them).
constexpr int kSlots = 32;
constexpr size_t kPathBytes = 4096;  // PATH_MAX on Linux
enum : int { kFree = 0, kClaimed = 1, kReady = 2 };
struct Slot {
    std::atomic<int> state{kFree};
    char path[kPathBytes];
};
std::array<Slot, kSlots> g_slots;

int register_temporary(const std::string& path)
{
    if (path.size() >= kPathBytes) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = kFree;
        if (g_slots[i].state.compare_exchange_strong(expected, kClaimed)) {
            std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
            g_slots[i].state.store(kReady, std::memory_order_release);
            return i;
        }
    }
    return -1;
}

void unregister_temporary(int slot)
{
    if (slot >= 0) g_slots[slot].state.store(kFree, std::memory_order_release);
}

/// A stream buffer over a file descriptor that remembers why a write failed: std::ofstream keeps
/// only "failed", and by the time anyone asks, errno has moved on (EFBIG past `ulimit -f` read as
/// "disk full?").
class FdBuffer final : public std::streambuf {
public:
    explicit FdBuffer(int fd) : fd_(fd) { setp(buf_, buf_ + sizeof buf_); }
    int error() const { return error_; }
    /// Writes what is buffered and closes the descriptor; false (error() says why) on failure.
    bool close()
    {
        const bool ok = flush_buffer();
        if (fd_ >= 0 && ::close(fd_) != 0 && error_ == 0) error_ = errno;
        fd_ = -1;
        return ok && error_ == 0;
    }
    ~FdBuffer() override
    {
        if (fd_ >= 0) ::close(fd_);
    }

protected:
    int_type overflow(int_type c) override
    {
        if (!flush_buffer()) return traits_type::eof();
        if (!traits_type::eq_int_type(c, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(c);
            pbump(1);
        }
        return traits_type::not_eof(c);
    }
    std::streamsize xsputn(const char* s, std::streamsize n) override
    {
        if (n >= std::streamsize(sizeof buf_)) {  // large writes go straight to the file
            if (!flush_buffer() || !write_all(s, size_t(n))) return 0;
            return n;
        }
        return std::streambuf::xsputn(s, n);
    }
    int sync() override { return flush_buffer() ? 0 : -1; }
    // Seeking, for a format written out of order (.hair a block of strands at a time): what is
    // buffered goes first; a descriptor that cannot seek (a pipe) fails with its reason kept.
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode which) override
    {
        if (!(which & std::ios_base::out) || !flush_buffer()) return pos_type(off_type(-1));
        const int whence = dir == std::ios_base::beg ? SEEK_SET : dir == std::ios_base::cur ? SEEK_CUR : SEEK_END;
        const off_t at = ::lseek(fd_, off_t(off), whence);
        if (at < 0) {
            if (error_ == 0) error_ = errno;
            return pos_type(off_type(-1));
        }
        return pos_type(off_type(at));
    }
    pos_type seekpos(pos_type pos, std::ios_base::openmode which) override { return seekoff(off_type(pos), std::ios_base::beg, which); }

private:
    bool write_all(const char* p, size_t n)
    {
        if (error_) return false;
        while (n > 0) {
            const ssize_t w = ::write(fd_, p, n);
            if (w < 0 && errno == EINTR) continue;
            if (w <= 0) {
                error_ = w < 0 ? errno : EIO;
                return false;
            }
            p += w;
            n -= size_t(w);
        }
        return true;
    }
    bool flush_buffer()
    {
        const size_t n = size_t(pptr() - pbase());
        setp(buf_, buf_ + sizeof buf_);
        return write_all(buf_, n);
    }

    int fd_;
    int error_ = 0;
    char buf_[1 << 16];
};

}  // namespace

struct AtomicOutput::File {
    explicit File(int fd) : buffer(fd), stream(&buffer) {}
    FdBuffer buffer;
    std::ostream stream;
};

void remove_temporaries_on_signal() noexcept
{
    for (Slot& s : g_slots) {
        if (s.state.load(std::memory_order_acquire) == kReady) ::unlink(s.path);
    }
}

bool written_in_place(const std::string& path)
{
    struct stat st {};
    return path != "-" && ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

AtomicOutput::AtomicOutput(std::string path, bool binary) : path_(std::move(path))
{
    if (path_ == "-") {
        to_stdout_ = true;
        return;
    }
    if (path_.empty()) throw IoError("output path is empty");
    // A device, a FIFO or a socket is written into as it is (`-o /dev/null`): renamed over, it was
    // replaced by a regular file (as root, /dev/null itself: a trial). Nothing can be undone there.
    // A folder is refused at open, not at the rename: by then a batch's earlier outputs had landed.
    std::error_code dir_ec;
    if (std::filesystem::is_directory(path_, dir_ec)) throw IoError(path_ + ": is a folder; expected a file to write");
    if (written_in_place(path_)) {
        const int fd = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd < 0) {
            const int err = errno;
            throw IoError(path_ + ": cannot open for writing (" + std::strerror(err) + ")");
        }
        file_ = std::make_unique<File>(fd);
        in_place_ = true;
        return;
    }
    // A symbolic link: its target is written (atomically, beside the target), the link kept; renamed
    // over, the link was replaced by a regular file and its target left as it was.
    // Followed link by link (weakly_canonical stops at a target that does not exist yet, and the
    // rename then replaced the link: a review), each relative to its own folder.
    std::error_code ec;
    std::filesystem::path at = path_;
    for (int hops = 0; hops < 40 && std::filesystem::is_symlink(at, ec); ++hops) {
        const std::filesystem::path to = std::filesystem::read_symlink(at, ec);
        if (ec) break;
        at = to.is_absolute() ? to : at.parent_path() / to;
    }
    if (at != std::filesystem::path(path_)) target_ = at.lexically_normal().string();
    temp_ = temp_name(target_.empty() ? path_ : target_);
    // Listed before the file exists: a signal between open and registration would leave it behind.
    slot_ = register_temporary(temp_);
    (void)binary;  // POSIX files have no text mode
    const int fd = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) {
        const int err = errno;
        unregister_temporary(slot_);
        throw IoError(path_ + ": cannot open for writing (" + std::strerror(err) + ")");
    }
    file_ = std::make_unique<File>(fd);
}

AtomicOutput::~AtomicOutput()
{
    if (in_place_) return;
    if (!committed_ && !to_stdout_) {
        file_.reset();
        std::remove(temp_.c_str());
    }
    unregister_temporary(slot_);
}

std::ostream& AtomicOutput::stream()
{
    return to_stdout_ ? std::cout : file_->stream;
}

void AtomicOutput::finish()
{
    if (finished_) return;
    if (to_stdout_) {
        std::cout.flush();
        if (!std::cout) throw IoError("error writing to standard output");
        finished_ = true;
        return;
    }
    // The reason of the write that failed (EFBIG past `ulimit -f`, ENOSPC on a full disk).
    const bool ok = file_->buffer.close() && !file_->stream.bad();
    if (!ok) {
        const int err = file_->buffer.error();
        // .hair is written a block at a time, each at its place: a FIFO or pipe cannot take that.
        const std::string why = err == ESPIPE ? "it cannot seek: this format is written at places, so write it to a file"
                                              : err ? std::string(std::strerror(err)) : std::string("stream error");
        throw IoError(path_ + ": write failed (" + why + ")");
    }
    finished_ = true;
}

void AtomicOutput::commit()
{
    finish();
    if (to_stdout_ || in_place_) {
        committed_ = true;
        return;
    }
    // A file replaced keeps its permissions (the temporary was made 0666 less the umask): a script
    // that rewrites a shared output must not change who may read it.
    const std::string& into = target_.empty() ? path_ : target_;
    struct stat old {};
    if (::stat(into.c_str(), &old) == 0 && S_ISREG(old.st_mode)) ::chmod(temp_.c_str(), old.st_mode & 07777);
    if (std::rename(temp_.c_str(), into.c_str()) != 0) {
        const int err = errno;
        std::remove(temp_.c_str());
        throw IoError(path_ + ": cannot rename temporary into place (" + std::strerror(err) + ")");
    }
    committed_ = true;
    unregister_temporary(slot_);
    slot_ = -1;
}

std::ostream& OutputBatch::open(const std::string& path, bool binary)
{
    files_.push_back(std::make_unique<AtomicOutput>(path, binary));
    return files_.back()->stream();
}

void OutputBatch::defer(std::function<void()> action)
{
    deferred_.push_back(std::move(action));
}

void OutputBatch::commit()
{
    for (auto& f : files_) f->finish();
    for (auto& f : files_) f->commit();
    for (auto& d : deferred_) d();
    files_.clear();
    deferred_.clear();
}

}  // namespace groom
