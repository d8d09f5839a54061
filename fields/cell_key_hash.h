// CellKeyHash: the hash of the tables that keep per-cell answers (fields/far_field.h,
// fields/near_faces.h). Their keys pack cell coordinates into bit fields, which std::hash's
// identity would send into long chains; this is MurmurHash3's 64-bit finaliser.
#pragma once

#include <cstddef>
#include <cstdint>

namespace groom::detail {

struct CellKeyHash {
    size_t operator()(uint64_t k) const
    {
        k ^= k >> 33;
        k *= 0xff51afd7ed558ccdull;
        k ^= k >> 33;
        k *= 0xc4ceb9fe1a85ec53ull;
        return size_t(k ^ (k >> 33));
    }
};

}  // namespace groom::detail
