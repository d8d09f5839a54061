#include "fields/clear_cells.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <new>

namespace groom::detail {

namespace {
constexpr int64_t kBlockVoxels = 512;  // 8^3
}

ClearCells::ClearCells(const int64_t lo[3], const int64_t n[3], float voxel) : quantum_(voxel / 16.0f)
{
    int64_t blocks = 1;
    for (int k = 0; k < 3; ++k) {
        lo_[k] = lo[k];
        n_[k] = std::max<int64_t>(n[k], 0);
        blocks = n_[k] > 0 && blocks <= kMaxBlocks / n_[k] ? blocks * n_[k] : kMaxBlocks + 1;
    }
    if (blocks > kMaxBlocks || !(quantum_ > 0.0f)) {
        n_[0] = n_[1] = n_[2] = 0;
        return;
    }
    // calloc: zero pages, only the ones a query reaches take memory. An all-zero atomic pointer is
    // a null one on every platform groom builds on.
    table_.reset(static_cast<std::atomic<uint8_t*>*>(std::calloc(size_t(blocks), sizeof(std::atomic<uint8_t*>))));
    if (!table_) throw std::bad_alloc();
}

ClearCells::~ClearCells()
{
    if (!table_) return;
    const int64_t count = n_[0] * n_[1] * n_[2];
    for (int64_t i = 0; i < count; ++i) delete[] table_[i].load(std::memory_order_relaxed);
}

void ClearCells::FreeTable::operator()(std::atomic<uint8_t*>* p) const { std::free(p); }

uint8_t* ClearCells::slot(int64_t vx, int64_t vy, int64_t vz) const
{
    const uint64_t bx = uint64_t((vx >> 3) - lo_[0]), by = uint64_t((vy >> 3) - lo_[1]), bz = uint64_t((vz >> 3) - lo_[2]);
    if (!(bx < uint64_t(n_[0]) && by < uint64_t(n_[1]) && bz < uint64_t(n_[2]))) return nullptr;
    std::atomic<uint8_t*>& entry = table_[(bx * uint64_t(n_[1]) + by) * uint64_t(n_[2]) + bz];
    uint8_t* block = entry.load(std::memory_order_acquire);
    if (!block) {
        uint8_t* mine = new uint8_t[kBlockVoxels]();
        if (entry.compare_exchange_strong(block, mine, std::memory_order_acq_rel, std::memory_order_acquire)) {
            block = mine;
            blocks_.fetch_add(1, std::memory_order_relaxed);
        }
        else {
            delete[] mine;  // another thread's block is in place (`block` holds it)
        }
    }
    return block + ((vx & 7) * 64 + (vy & 7) * 8 + (vz & 7));
}

uint8_t ClearCells::encode(float lower) const
{
    // Rounded down, and a millionth below that: the code's value, (code - 1) * quantum in float,
    // never exceeds the bound it stands for.
    const double steps = std::floor(double(lower) / double(quantum_) * (1.0 - 1e-6));
    if (!(steps >= 1.0)) return kNothing;
    return uint8_t(kNothing + std::min(steps, 254.0));
}

}  // namespace groom::detail
