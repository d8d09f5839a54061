#include "fields/winding_number.h"

#include "kernel/parallel.h"

#include <algorithm>
#include <cmath>

namespace groom::detail {

namespace {

constexpr int kLeafSize = 8;

/// Solid angle of triangle (a, b, c) seen from the origin (Van Oosterom & Strackee 1983).
double solid_angle(const float3& fa, const float3& fb, const float3& fc)
{
    const double a[3] = {fa.x, fa.y, fa.z}, b[3] = {fb.x, fb.y, fb.z}, c[3] = {fc.x, fc.y, fc.z};
    auto dot3 = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
    const double la = std::sqrt(dot3(a, a)), lb = std::sqrt(dot3(b, b)), lc = std::sqrt(dot3(c, c));
    const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    const double den = la * lb * lc + dot3(a, b) * lc + dot3(a, c) * lb + dot3(b, c) * la;
    // The single-precision arctangent: half the cost of the double one, and its 1e-7 relative error
    // is far below what the far field leaves.
    return 2.0 * double(std::atan2(float(det), float(den)));
}

}  // namespace

WindingNumber::WindingNumber(std::span<const float3> points, std::span<const std::array<int32_t, 3>> triangles)
{
    const size_t n = triangles.size();
    corners_.resize(n * 3);
    centroids_.resize(n);
    areas_.resize(n);
    order_.resize(n);
    for (size_t t = 0; t < n; ++t) {
        for (int k = 0; k < 3; ++k) corners_[t * 3 + k] = points[triangles[t][k]];
        centroids_[t] = (corners_[t * 3] + corners_[t * 3 + 1] + corners_[t * 3 + 2]) / 3.0f;
        areas_[t] = cross(corners_[t * 3 + 1] - corners_[t * 3], corners_[t * 3 + 2] - corners_[t * 3]) * 0.5f;
        radii_.push_back(std::max({distance(corners_[t * 3], centroids_[t]), distance(corners_[t * 3 + 1], centroids_[t]),
                                   distance(corners_[t * 3 + 2], centroids_[t])}));
        order_[t] = int32_t(t);
    }
    nodes_.reserve(n / kLeafSize * 2 + 1);
    if (n > 0) build(0, int32_t(n));
}

int32_t WindingNumber::build(int32_t begin, int32_t end)
{
    const int32_t id = int32_t(nodes_.size());
    nodes_.emplace_back();
    // Area-weighted centre and total area vector, then the radius reaching every corner.
    double cx = 0, cy = 0, cz = 0, total = 0;
    float3 area;
    Bounds3 box;
    for (int32_t i = begin; i < end; ++i) {
        const int32_t t = order_[i];
        const double w = double(length(areas_[t])) + 1e-30;
        cx += w * centroids_[t].x, cy += w * centroids_[t].y, cz += w * centroids_[t].z;
        total += w;
        area += areas_[t];
        box.extend(centroids_[t]);
    }
    const float3 center(float(cx / total), float(cy / total), float(cz / total));
    float radius = 0.0f;
    double second[9] = {};
    for (int32_t i = begin; i < end; ++i) {
        const int32_t t = order_[i];
        for (int k = 0; k < 3; ++k) radius = std::max(radius, distance(corners_[t * 3 + k], center));
        const float3& a = areas_[t];
        const float3 g = centroids_[t] - center;
        const double av[3] = {a.x, a.y, a.z}, gv[3] = {g.x, g.y, g.z};
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) second[r * 3 + c] += av[r] * gv[c];
    }
    for (int k = 0; k < 9; ++k) nodes_[id].second[k] = float(second[k]);
    nodes_[id].center = center;
    nodes_[id].radius = radius;
    nodes_[id].area = area;
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    if (end - begin > kLeafSize) {
        // Median split of the centroids along the box's longest axis.
        const float3 extent = box.hi - box.lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
        auto key = [&](int32_t t) { return axis == 0 ? centroids_[t].x : axis == 1 ? centroids_[t].y : centroids_[t].z; };
        const int32_t mid = begin + (end - begin) / 2;
        std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                         [&](int32_t a, int32_t b) { return key(a) < key(b) || (key(a) == key(b) && a < b); });
        const int32_t left = build(begin, mid);
        const int32_t right = build(mid, end);
        nodes_[id].left = left;  // after the calls: they grow nodes_
        nodes_[id].right = right;
    }
    return id;
}

double WindingNumber::operator()(const float3& p, double far) const
{
    if (nodes_.empty()) return 0.0;
    double omega = 0.0;
    // Depth first; the tree is balanced (median splits), so 64 entries hold 2^32 leaves' worth.
    int32_t stack[64];
    int depth = 0;
    stack[depth++] = 0;
    while (depth > 0) {
        const Node& node = nodes_[stack[--depth]];
        const float3 r = node.center - p;
        const double d = double(length(r));
        if (d > far * double(node.radius)) {
            // The kernel (x - p) / |x - p|^3 expanded about the centre to first order: the dipole
            // A . r / d^3, then sum_t a_t . J (g_t - c) with J = I / d^3 - 3 r r^T / d^5.
            const double d3 = d * d * d, d5 = d3 * d * d;
            const double rv[3] = {r.x, r.y, r.z};
            const float* m = node.second;
            double rmr = 0.0;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) rmr += rv[i] * double(m[i * 3 + j]) * rv[j];
            const double trace = double(m[0]) + double(m[4]) + double(m[8]);
            omega += double(dot(node.area, r)) / d3 + trace / d3 - 3.0 * rmr / d5;
            continue;
        }
        if (node.left < 0) {
            for (int32_t i = node.begin; i < node.end; ++i) {
                // A leaf's triangles by the same rule: far ones by their own dipole (the second-order
                // term of one triangle about its centroid is zero), near ones exactly.
                const int32_t t = order_[i];
                const float3 rt = centroids_[t] - p;
                const double dt = double(length(rt));
                if (dt > far * double(radii_[t])) omega += double(dot(areas_[t], rt)) / (dt * dt * dt);
                else omega += solid_angle(corners_[t * 3] - p, corners_[t * 3 + 1] - p, corners_[t * 3 + 2] - p);
            }
            continue;
        }
        stack[depth++] = node.right;
        stack[depth++] = node.left;
    }
    return omega / (4.0 * M_PI);
}

double WindingNumber::exact(const float3& p) const
{
    constexpr int64_t kChunk = 2048;
    const int64_t n = int64_t(centroids_.size());
    std::vector<double> partial(size_t((n + kChunk - 1) / kChunk), 0.0);
    parallel_for(int64_t(partial.size()), 1, [&](int64_t begin, int64_t end) {
        for (int64_t c = begin; c < end; ++c) {
            double sum = 0.0;
            for (int64_t t = c * kChunk; t < std::min(n, (c + 1) * kChunk); ++t) {
                sum += solid_angle(corners_[t * 3] - p, corners_[t * 3 + 1] - p, corners_[t * 3 + 2] - p);
            }
            partial[size_t(c)] = sum;
        }
    });
    double omega = 0.0;
    for (double x : partial) omega += x;
    return omega / (4.0 * M_PI);
}

}  // namespace groom::detail
