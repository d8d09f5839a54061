#include "kernel/curve_blocks.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <future>
#include <memory>

namespace groom {

std::vector<int64_t> curve_block_ends(std::span<const int64_t> counts, int64_t block_points)
{
    std::vector<int64_t> ends;
    int64_t held = 0;
    for (size_t c = 0; c < counts.size(); ++c) {
        held += counts[c];
        if (held >= block_points || c + 1 == counts.size()) {
            ends.push_back(int64_t(c) + 1);
            held = 0;
        }
    }
    return ends;
}

int64_t largest_curve_block(std::span<const int64_t> counts, std::span<const int64_t> ends)
{
    int64_t largest = 0, c0 = 0;
    for (const int64_t c1 : ends) {
        int64_t held = 0;
        for (int64_t c = c0; c < c1; ++c) held += counts[size_t(c)];
        largest = std::max(largest, held);
        c0 = c1;
    }
    return largest;
}

void hand_over_curve_blocks(std::span<const int64_t> ends, const std::function<CurveSet(int64_t c0, int64_t c1)>& make,
                            const std::function<void(const CurveSet& block)>& emit)
{
    const bool overlap = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1;
    std::future<void> handing;  // joined by its destructor if make() throws
    int64_t c0 = 0;
    for (const int64_t c1 : ends) {
        auto block = std::make_shared<CurveSet>(make(c0, c1));
        if (handing.valid()) handing.get();  // in order, one at a time; its error is thrown here
        if (overlap) handing = std::async(std::launch::async, [&emit, block] { emit(*block); });
        else emit(*block);
        c0 = c1;
    }
    if (handing.valid()) handing.get();
}

}  // namespace groom
