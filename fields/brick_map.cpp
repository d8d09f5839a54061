#include "fields/brick_map.h"

#include "kernel/parallel.h"

#include <sys/mman.h>

#include <cmath>
#include <limits>
#include <new>
#include <utility>

namespace groom::detail {

namespace {

constexpr size_t kHugePage = size_t(2) << 20;

uint32_t hash(int32_t x, int32_t y, int32_t z)
{
    const uint64_t h = uint64_t(uint32_t(x)) * 0x9E3779B97F4A7C15ull ^ uint64_t(uint32_t(y)) * 0xC2B2AE3D27D4EB4Full ^
                       uint64_t(uint32_t(z)) * 0x165667B19E3779F9ull;
    return uint32_t(h >> 32);
}

}  // namespace

BandValue BrickMap::outside() { return {std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f, 0.0f}; }

BrickMap::BrickMap(BrickMap&& o) noexcept { *this = std::move(o); }

BrickMap& BrickMap::operator=(BrickMap&& o) noexcept
{
    if (this != &o) {
        release();
        slots_ = std::move(o.slots_);
        mask_ = o.mask_;
        origins_ = std::move(o.origins_);
        whole_ = std::move(o.whole_);
        values_ = std::exchange(o.values_, nullptr);
        mapped_bytes_ = std::exchange(o.mapped_bytes_, 0);
    }
    return *this;
}

BrickMap::~BrickMap() { release(); }

void BrickMap::release()
{
    if (values_) ::munmap(values_, mapped_bytes_);
    values_ = nullptr;
    mapped_bytes_ = 0;
}

void BrickMap::allocate(const std::vector<openvdb::Coord>& leaf_origins)
{
    release();
    origins_ = leaf_origins;
    whole_.assign(leaf_origins.size() * 8, 0);
    const size_t n = origins_.size();
    size_t capacity = 16;
    while (capacity < 2 * n) capacity *= 2;
    slots_.assign(capacity, Slot{0, 0, 0, -1});
    mask_ = uint32_t(capacity - 1);
    for (size_t b = 0; b < n; ++b) {
        const int32_t x = origins_[b].x() >> 3, y = origins_[b].y() >> 3, z = origins_[b].z() >> 3;
        uint32_t i = hash(x, y, z) & mask_;
        while (slots_[i].brick >= 0) i = (i + 1) & mask_;
        slots_[i] = Slot{x, y, z, int32_t(b)};
    }
    if (n == 0) return;

    // A 2 MiB-aligned anonymous mapping, advised onto huge pages (transparent huge pages are
    // "madvise" on Debian): the bricks of a head span tens of MiB, which 4 KiB pages would turn into
    // a TLB miss per query.
    const size_t bytes = (n * kVolume * sizeof(BandValue) + kHugePage - 1) / kHugePage * kHugePage;
    void* raw = ::mmap(nullptr, bytes + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    char* base = static_cast<char*>(raw);
    char* aligned = reinterpret_cast<char*>((reinterpret_cast<uintptr_t>(base) + kHugePage - 1) / kHugePage * kHugePage);
    if (aligned > base) ::munmap(base, size_t(aligned - base));
    const size_t tail = size_t(base + bytes + kHugePage - (aligned + bytes));
    if (tail > 0) ::munmap(aligned + bytes, tail);
    ::madvise(aligned, bytes, MADV_HUGEPAGE);  // advice only: without it the map still works
    values_ = reinterpret_cast<BandValue*>(aligned);
    mapped_bytes_ = bytes;
    const BandValue out = outside();
    parallel_for(int64_t(n), 16, [&](int64_t begin, int64_t end) {
        for (int64_t b = begin; b < end; ++b) {
            BandValue* v = brick(size_t(b));
            for (int i = 0; i < kVolume; ++i) v[i] = out;
        }
    });
}

int32_t BrickMap::find(int32_t lx, int32_t ly, int32_t lz) const
{
    for (uint32_t i = hash(lx, ly, lz) & mask_;; i = (i + 1) & mask_) {
        const Slot& s = slots_[i];
        if (s.brick < 0) return -1;
        if (s.x == lx && s.y == ly && s.z == lz) return s.brick;
    }
}

void BrickMap::fill_borders()
{
    // Borders are written, interiors only read: bricks can be done in any order, in parallel.
    parallel_for(int64_t(num_bricks()), 16, [&](int64_t begin, int64_t end) {
        for (int64_t b = begin; b < end; ++b) {
            BandValue* v = brick(size_t(b));
            const int32_t lx = origins_[b].x() >> 3, ly = origins_[b].y() >> 3, lz = origins_[b].z() >> 3;
            int32_t neighbour[8];
            for (int k = 1; k < 8; ++k) neighbour[k] = find(lx + (k & 1), ly + ((k >> 1) & 1), lz + ((k >> 2) & 1));
            for (int x = 0; x < kSide; ++x) {
                for (int y = 0; y < kSide; ++y) {
                    for (int z = 0; z < kSide; ++z) {
                        const int k = (x >> 3) | ((y >> 3) << 1) | ((z >> 3) << 2);
                        if (k == 0) continue;
                        const int32_t nb = neighbour[k];
                        v[index(x, y, z)] = nb >= 0 ? brick(size_t(nb))[index(x & 7, y & 7, z & 7)] : outside();
                    }
                }
            }
            // Which cells have every corner in the band (a NaN distance marks a voxel outside it).
            uint64_t* bits = &whole_[size_t(b) * 8];
            for (int x = 0; x < kLeaf; ++x) {
                uint64_t word = 0;
                for (int y = 0; y < kLeaf; ++y) {
                    for (int z = 0; z < kLeaf; ++z) {
                        bool in = true;
                        for (int k = 0; k < 8; ++k) in = in && !std::isnan(v[index(x + (k & 1), y + ((k >> 1) & 1), z + ((k >> 2) & 1))].d);
                        if (in) word |= uint64_t(1) << (y * kLeaf + z);
                    }
                }
                bits[x] = word;
            }
        }
    });
}

bool BrickMap::interpolate(float x, float y, float z, float r[4], bool whole) const
{
    if (!values_) return false;  // no band at all
    if (!(std::fabs(x) < 1e9f && std::fabs(y) < 1e9f && std::fabs(z) < 1e9f)) return false;  // also NaN
    const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const int32_t ix = int32_t(fx), iy = int32_t(fy), iz = int32_t(fz);
    const int32_t b = find(ix >> 3, iy >> 3, iz >> 3);
    if (b < 0) return false;
    if (whole && !((whole_[size_t(b) * 8 + size_t(ix & 7)] >> ((iy & 7) * kLeaf + (iz & 7))) & 1)) return false;
    const float* c = &values_[size_t(b) * kVolume + size_t(index(ix & 7, iy & 7, iz & 7))].d;
    const float tx = x - fx, ty = y - fy, tz = z - fz;
    constexpr int kY = kSide * 4, kX = kSide * kSide * 4;  // strides in floats; z neighbours are adjacent
    for (int i = 0; i < 4; ++i) {
        const float c00 = c[i] + (c[i + 4] - c[i]) * tz;
        const float c01 = c[kY + i] + (c[kY + 4 + i] - c[kY + i]) * tz;
        const float c10 = c[kX + i] + (c[kX + 4 + i] - c[kX + i]) * tz;
        const float c11 = c[kX + kY + i] + (c[kX + kY + 4 + i] - c[kX + kY + i]) * tz;
        const float c0 = c00 + (c01 - c00) * ty, c1 = c10 + (c11 - c10) * ty;
        r[i] = c0 + (c1 - c0) * tx;
    }
    return true;
}

bool BrickMap::sample(float x, float y, float z, BandValue& out) const
{
    float r[4];
    // A corner outside the band fails the sample even where it has no weight (as 0 * NaN = NaN did
    // when the corners were interpolated first), which keeps the band's edge where it was.
    if (!interpolate(x, y, z, r, true)) return false;
    out = BandValue{r[0], r[1], r[2], r[3]};
    return true;
}

bool BrickMap::cell_corners(int32_t ix, int32_t iy, int32_t iz, BandValue out[8]) const
{
    if (!values_) return false;
    const int32_t b = find(ix >> 3, iy >> 3, iz >> 3);
    if (b < 0 || !((whole_[size_t(b) * 8 + size_t(ix & 7)] >> ((iy & 7) * kLeaf + (iz & 7))) & 1)) return false;
    const BandValue* c = &values_[size_t(b) * kVolume + size_t(index(ix & 7, iy & 7, iz & 7))];
    for (int k = 0; k < 8; ++k) out[k] = c[index(k & 1, (k >> 1) & 1, (k >> 2) & 1)];
    return true;
}

bool BrickMap::gradient(float x, float y, float z, float& gx, float& gy, float& gz) const
{
    float r[4];
    if (!interpolate(x, y, z, r, false)) return false;
    gx = r[1], gy = r[2], gz = r[3];
    return true;
}

}  // namespace groom::detail
