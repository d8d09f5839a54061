// BrickMap: the scalp's narrow band laid out for queries. OpenVDB's tree is the right structure to
// build, store and exchange a level set, but a random point query walks two internal-node tables
// and reads leaves scattered over the heap in 4 KiB pages: on a head-sized grid each of those is a
// cache and TLB miss, and the stalled loads, not the arithmetic, were 70% of a projection. Here every leaf of
// the band becomes a brick of 9^3 values (the leaf plus the first layer of its +x, +y and +z
// neighbours, so the 8 corners of any trilinear cell lie in one brick) in one contiguous block on
// huge pages, found by a small open-addressing hash of leaf coordinates: one probe, then four
// cache lines per sample.
#pragma once

#include <openvdb/openvdb.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace groom::detail {

/// Signed distance and its unit gradient (the outward normal) side by side: one read fetches both.
struct BandValue {
    float d, nx, ny, nz;
};

class BrickMap {
public:
    static constexpr int kLeaf = 8;   ///< OpenVDB leaf side (voxels)
    static constexpr int kSide = 9;   ///< brick side: the leaf plus one layer of neighbours
    static constexpr int kVolume = kSide * kSide * kSide;

    BrickMap() = default;
    BrickMap(BrickMap&&) noexcept;
    BrickMap& operator=(BrickMap&&) noexcept;
    BrickMap(const BrickMap&) = delete;
    BrickMap& operator=(const BrickMap&) = delete;
    ~BrickMap();

    /// One brick per leaf origin (multiples of 8, distinct), every value outside the band.
    void allocate(const std::vector<openvdb::Coord>& leaf_origins);
    size_t num_bricks() const { return origins_.size(); }
    /// Brick `b` (in allocate()'s order); local voxel (x, y, z) in [0, 8]^3 is at index(x, y, z).
    BandValue* brick(size_t b) { return values_ + b * kVolume; }
    static constexpr int index(int x, int y, int z) { return (x * kSide + y) * kSide + z; }
    /// Copies each brick's +x, +y and +z border layer from its neighbours (outside the band where
    /// there is none), and notes which cells have all 8 corners in the band. Call once, after every
    /// brick's 8^3 interior is filled.
    void fill_borders();

    /// Trilinear distance and gradient at index-space position (x, y, z). False when any of the 8
    /// corners is outside the band (or the position is not finite).
    bool sample(float x, float y, float z, BandValue& out) const;
    /// Trilinear gradient alone, over the corners that are in the band (a corner outside it holds
    /// a zero gradient, which shortens the result without turning it): the band's normal reaches
    /// cells at its edge whose distance sample() refuses. False only where no brick holds the cell.
    bool gradient(float x, float y, float z, float& gx, float& gy, float& gz) const;

    /// The 8 corners of the trilinear cell [ix, ix + 1] x [iy, iy + 1] x [iz, iz + 1] (voxel
    /// indices), corner k at (ix + (k & 1), iy + (k >> 1 & 1), iz + (k >> 2 & 1)): what sample()
    /// interpolates in that cell. False where sample() fails there (a corner outside the band).
    bool cell_corners(int32_t ix, int32_t iy, int32_t iz, BandValue out[8]) const;

    /// Value marking a voxel outside the band: NaN distance, which any interpolation carries along,
    /// and a zero gradient, which gradient() may average in.
    static BandValue outside();

private:
    /// Trilinear interpolation of all four channels at (x, y, z); false where no brick holds the
    /// cell, or, with `whole`, where a corner of the cell is outside the band.
    bool interpolate(float x, float y, float z, float r[4], bool whole) const;
    /// Brick of the leaf with origin (8 lx, 8 ly, 8 lz), or -1.
    int32_t find(int32_t lx, int32_t ly, int32_t lz) const;
    void release();

    struct Slot {
        int32_t x, y, z, brick;
    };
    std::vector<Slot> slots_;
    uint32_t mask_ = 0;
    std::vector<openvdb::Coord> origins_;
    BandValue* values_ = nullptr;
    size_t mapped_bytes_ = 0;
    // Per brick, one bit per cell of its leaf (512, 64 bytes): set where all 8 corners are in the
    // band. sample() reads it before the corners: on Sintel's curl --scalp half the points that
    // find a brick are outside the band (1.6M of 3.1M), and each read its four cache lines of a
    // brick (11.7 KB, rarely cached) to find a NaN; the bits of every brick take 64 bytes each.
    std::vector<uint64_t> whole_;
};

}  // namespace groom::detail
