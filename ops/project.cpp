#include "ops/project.h"
#include "ops/root_uv.h"

#include "kernel/error.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <cmath>

namespace groom {

void ProjectParams::validate() const
{
    if (!std::isfinite(offset)) throw InvalidParam("project: `offset` must be a finite distance (got " + std::to_string(offset) + ")");
}

CurveSet project(const CurveSet& src, const Surface& scalp, const ProjectParams& params, ProjectStats* stats)
{
    params.validate();
    // The output is a copy of the input (every column) plus root UVs, and per curve a distance and a
    // count; bounded by the input, but a copy all the same: estimated like every op's output.
    const double curves = double(src.num_curves()), points = double(src.num_points());
    check_memory("project: a copy of " + std::to_string(src.num_points()) + " points in " + std::to_string(src.num_curves()) +
                     " curves (the input)",
                 points * bytes_per_point(src) + curves * (bytes_per_curve(src) + 8.0 + 4.0 + 8.0),
                 "project fewer curves at a time, e.g. parts chosen with groom select --ids");
    CurveSet dst = src;
    const auto P = dst.positions_for_write();
    const int64_t nc = static_cast<int64_t>(dst.num_curves());
    std::vector<float> moved(nc, 0.0f);
    std::vector<int64_t> count(nc, 0);
    parallel_for(nc, 64, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = dst.points_of(size_t(c));
            if (r.empty()) continue;
            if (params.mode == ProjectMode::Root) {
                const float3 root = P[r.begin];
                const float3 target = scalp.closest_point(root) + scalp.normal(root) * params.offset;
                const float3 shift = target - root;
                for (int64_t i = r.begin; i < r.end; ++i) P[i] += shift;
                moved[c] = length(shift);
                count[c] = r.size();
            }
            else {
                for (int64_t i = r.begin; i < r.end; ++i) {
                    const float3 p = P[i];
                    P[i] = scalp.closest_point(p) + scalp.normal(p) * params.offset;
                    moved[c] = std::max(moved[c], distance(P[i], p));
                }
                count[c] = r.size();
            }
        }
    });
    if (stats) {
        *stats = ProjectStats{};
        stats->curves = nc;
        for (int64_t c = 0; c < nc; ++c) {
            stats->points_moved += count[c];
            stats->max_move = std::max(stats->max_move, double(moved[c]));
        }
    }
    add_root_uvs(dst, scalp);
    return dst;
}

}  // namespace groom
