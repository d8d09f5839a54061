// Curve blocks: an op's output made and handed over a block of curves at a time, for a caller that
// writes it as it is made and never holds it whole (`groom curl` and `groom generate` into .hair:
// a million hairs' output held whole, beside the input, was twice the file).
#pragma once

#include "kernel/curve_set.h"

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace groom {

/// Points a block holds when an output is written as it is made: large enough that every thread
/// has curves to share (thousands of hairs), small enough that the last block's write, which
/// nothing hides, is short (4 MB of positions and widths; 2^20 points measured 3% slower on
/// Sintel's 100,000 curled hairs at 2 threads).
inline constexpr int64_t kCurveBlockPoints = int64_t(1) << 18;

/// Where blocks of curves with these point counts end: each at the first curve that brings it to
/// `block_points` points (a curve is never split; the last block takes what is left). Empty for no curves.
std::vector<int64_t> curve_block_ends(std::span<const int64_t> counts, int64_t block_points);

/// The points of the largest block that `ends` cuts `counts` into (what a caller holds at once).
int64_t largest_curve_block(std::span<const int64_t> counts, std::span<const int64_t> ends);

/// Makes block k = 0, 1, ... (curves [ends[k-1], ends[k])) with `make` and hands each to `emit` in
/// order, one call at a time. With more than one thread allowed, a block is handed over from
/// another thread while the next is made (writing the file was the serial part of such an op); an
/// exception from either is rethrown here, after the block in flight is done.
void hand_over_curve_blocks(std::span<const int64_t> ends, const std::function<CurveSet(int64_t c0, int64_t c1)>& make,
                            const std::function<void(const CurveSet& block)>& emit);

}  // namespace groom
