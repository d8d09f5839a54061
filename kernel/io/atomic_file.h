// Atomic output: write to a temporary file beside the target, rename over it when complete. If
// anything throws before commit(), the temporary is removed and the target is left untouched.
#pragma once

#include <fstream>
#include <ostream>
#include <string>

namespace groom {

class AtomicOutput {
public:
    /// Opens a temporary beside `path` (or stdout when path is "-"). Throws IoError.
    explicit AtomicOutput(std::string path, bool binary = true);
    ~AtomicOutput();
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;

    std::ostream& stream();
    /// Flushes and renames the temporary onto the target. Throws IoError.
    void commit();
    const std::string& path() const { return path_; }

private:
    std::string path_, temp_;
    std::ofstream file_;
    bool committed_ = false;
    bool to_stdout_ = false;
};

}  // namespace groom
