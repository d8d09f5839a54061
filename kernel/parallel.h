// Parallel helpers over TBB. Work is split into index ranges; each task writes only its own slice
// of the output, so results never depend on the thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace groom {

/// Calls fn(begin, end) over [0, n) in parallel chunks of about `grain` indices.
template <class Fn> void parallel_for(int64_t n, int64_t grain, Fn&& fn)
{
    if (n <= 0) return;
    if (n <= grain) {
        fn(int64_t(0), n);
        return;
    }
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, n, grain > 0 ? grain : 1),
                      [&](const tbb::blocked_range<int64_t>& r) { fn(r.begin(), r.end()); });
}

/// Caps the number of worker threads for the lifetime of the object (the CLI's --threads).
/// 0 means TBB's default (all cores).
class ThreadLimit {
public:
    explicit ThreadLimit(int threads);
    ~ThreadLimit();
    ThreadLimit(const ThreadLimit&) = delete;
    ThreadLimit& operator=(const ThreadLimit&) = delete;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Exclusive prefix sum of counts into offsets (size counts+1): the count -> scan -> fill pattern.
template <class T, class Counts> std::vector<T> offsets_from_counts(const Counts& counts)
{
    std::vector<T> offsets(counts.size() + 1, 0);
    for (size_t i = 0; i < counts.size(); ++i) offsets[i + 1] = offsets[i] + static_cast<T>(counts[i]);
    return offsets;
}

}  // namespace groom
