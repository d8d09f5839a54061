#include "kernel/io/atomic_file.h"

#include "kernel/error.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <unistd.h>

namespace groom {

namespace {
std::string temp_name(const std::string& path)
{
    static std::atomic<unsigned> counter{0};
    // Same directory as the target so rename() is atomic (no cross-device move).
    return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
}
}  // namespace

AtomicOutput::AtomicOutput(std::string path, bool binary) : path_(std::move(path))
{
    if (path_ == "-") {
        to_stdout_ = true;
        return;
    }
    if (path_.empty()) throw IoError("output path is empty");
    temp_ = temp_name(path_);
    file_.open(temp_, binary ? std::ios::out | std::ios::binary | std::ios::trunc : std::ios::out | std::ios::trunc);
    if (!file_) throw IoError(path_ + ": cannot open for writing (" + std::strerror(errno) + ")");
}

AtomicOutput::~AtomicOutput()
{
    if (!committed_ && !to_stdout_) {
        file_.close();
        std::remove(temp_.c_str());
    }
}

std::ostream& AtomicOutput::stream()
{
    return to_stdout_ ? std::cout : static_cast<std::ostream&>(file_);
}

void AtomicOutput::commit()
{
    if (to_stdout_) {
        std::cout.flush();
        if (!std::cout) throw IoError("error writing to standard output");
        committed_ = true;
        return;
    }
    file_.flush();
    const bool ok = static_cast<bool>(file_);
    file_.close();
    if (!ok) throw IoError(path_ + ": write failed (disk full?)");
    if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
        const int err = errno;
        std::remove(temp_.c_str());
        throw IoError(path_ + ": cannot rename temporary into place (" + std::strerror(err) + ")");
    }
    committed_ = true;
}

}  // namespace groom
