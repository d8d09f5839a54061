#include "ops/root_uv.h"

#include "kernel/parallel.h"

namespace groom {

void add_root_uvs(CurveSet& curves, const Surface& scalp)
{
    if (!scalp.has_uvs()) return;
    const auto P = curves.positions();
    const auto offsets = curves.offsets();
    const std::span<float3> uv = curves.add<float3>(Domain::Curve, "root_uv");
    parallel_for(int64_t(curves.num_curves()), 256, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            float u = 0.0f, v = 0.0f;
            if (offsets[c + 1] > offsets[c]) scalp.surface_uv(P[size_t(offsets[c])], u, v);
            uv[size_t(c)] = float3(u, v, 0.0f);
        }
    });
}

}  // namespace groom
