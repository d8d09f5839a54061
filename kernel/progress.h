// Progress reporting from long ops back to whoever drives them (the CLI draws a bar). Ops never
// print; they call these hooks, which must be thread-safe because tasks call advance() concurrently.
#pragma once

#include <cstdint>
#include <string_view>

namespace groom {

class Progress {
public:
    virtual ~Progress() = default;
    /// A new step of `total` units of work begins.
    virtual void begin(std::string_view label, int64_t total) = 0;
    /// `n` more units are done. Called from worker threads.
    virtual void advance(int64_t n) = 0;
    /// The step is complete.
    virtual void end() = 0;
};

/// RAII step over an optional Progress: does nothing when `p` is null.
class ProgressStep {
public:
    ProgressStep(Progress* p, std::string_view label, int64_t total) : p_(p)
    {
        if (p_) p_->begin(label, total);
    }
    ~ProgressStep()
    {
        if (p_) p_->end();
    }
    void advance(int64_t n) const
    {
        if (p_) p_->advance(n);
    }
    ProgressStep(const ProgressStep&) = delete;
    ProgressStep& operator=(const ProgressStep&) = delete;

private:
    Progress* p_;
};

}  // namespace groom
