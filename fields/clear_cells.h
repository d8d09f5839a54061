// ClearCells: per voxel of the level set's grid, how far outside the scalp every point of the voxel
// is known to be, as the field answers it: a lower bound of ScalpField::distance_within over the
// whole voxel (the band's trilinear values, or the far field's certificate), kept in one byte.
//
// Why: the rule that keeps hair out of the scalp (fields/keep_outside.h) asks one question of every
// point, "is it at least `need` outside?", and nearly always the answer is yes. Asked in full, each
// question finds the band's brick and reads its corners, or walks the far field's cells; on Sintel's
// curl --scalp that was 3.6 million questions at about 90 ns, a third of the run. The 3.2 million
// curled points lie in 327,000 voxels, so a voxel's answer, worked out once, serves ten points.
//
// Voxels are kept in blocks of 8^3 bytes, allocated on first use over a box around the mesh (a
// table of pointers, zero pages from calloc until touched): the memory follows where the queries
// go, 512 bytes per 8-voxel cell reached. A byte is written once per voxel with a pure function of
// the voxel, so threads that race store the same value and no lock is needed.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>

namespace groom::detail {

class ClearCells {
public:
    /// Blocks of 8^3 voxels; block (bx, by, bz) holds voxels [8 bx, 8 bx + 8) etc., for bx in
    /// [lo[0], lo[0] + n[0]). `voxel`: the grid's voxel size (the bounds are kept in 1/16 of it).
    ClearCells(const int64_t lo[3], const int64_t n[3], float voxel);
    ~ClearCells();
    ClearCells(const ClearCells&) = delete;
    ClearCells& operator=(const ClearCells&) = delete;

    /// Blocks the table may index at most (a pointer each, 32 MiB of address space; the pages
    /// no query reaches cost nothing). A larger box gets no table and every question is asked in full.
    static constexpr int64_t kMaxBlocks = int64_t(1) << 22;

    /// Code of a voxel not yet worked out; of one where nothing is known (inside, on the surface,
    /// beside an open rim, or less than a 16th of a voxel out).
    static constexpr uint8_t kUnknown = 0, kNothing = 1;

    /// The voxel's byte, its block allocated on first use; null outside the box.
    uint8_t* slot(int64_t vx, int64_t vy, int64_t vz) const;
    /// The code for a lower bound (scene units), rounded down to 1/16 voxel, at most 254/16 voxels.
    uint8_t encode(float lower) const;
    /// The lower bound a code stands for: 0 for kUnknown and kNothing.
    float decode(uint8_t code) const { return code > kNothing ? float(code - kNothing) * quantum_ : 0.0f; }

    /// Blocks allocated so far (for tests and benchmarks).
    int64_t blocks() const { return blocks_.load(std::memory_order_relaxed); }

private:
    struct FreeTable {
        void operator()(std::atomic<uint8_t*>* p) const;
    };
    std::unique_ptr<std::atomic<uint8_t*>[], FreeTable> table_;
    int64_t lo_[3] = {0, 0, 0}, n_[3] = {0, 0, 0};
    float quantum_ = 0.0f;
    mutable std::atomic<int64_t> blocks_{0};
};

}  // namespace groom::detail
