#include "ops/cranium.h"

#include "kernel/error.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace groom {

Cranium fit_cranium(const Surface& scalp, const HairRegion& region, const float3& up)
{
    if (!region.has_hairline()) throw InvalidGeometry("cranium: a hairline is needed to fit the cranium to the scalp inside it");
    const float3 Y = normalize(up);
    const float3 mid = region.centroid();
    float reach = 0.0f;
    for (const float3& q : region.hairline_points()) reach = std::max(reach, distance(q, mid));
    // Rays start this far out: past any head whose hairline is `reach` round (the scalp's own
    // bounds may hold a body).
    const float far = 8.0f * std::max(reach, 1e-6f);
    const float3 X = any_perpendicular(Y), Z = cross(X, Y);
    // A Fibonacci spiral over the directions above 20 degrees below the horizontal: even, and the
    // same points every run.
    constexpr int kRays = 1024;
    const float lowest = -std::sin(20.0f * 3.14159265f / 180.0f);
    const float golden = 3.14159265f * (3.0f - std::sqrt(5.0f));
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    Eigen::Vector4d b = Eigen::Vector4d::Zero();
    int used = 0;
    for (int k = 0; k < kRays; ++k) {
        const float h = 1.0f - (1.0f - lowest) * (float(k) + 0.5f) / float(kRays);  // height along Y, 1 .. lowest
        const float ring = std::sqrt(std::max(0.0f, 1.0f - h * h));
        const float t = golden * float(k);
        const float3 d = Y * h + X * (ring * std::cos(t)) + Z * (ring * std::sin(t));
        float3 hit;
        if (!scalp.first_intersection(mid + d * far, mid, hit)) continue;
        if (!region.inside_hairline(hit)) continue;
        // Relative to the centroid, for the conditioning of the normal equations.
        const Eigen::Vector4d row(2.0 * double(hit.x - mid.x), 2.0 * double(hit.y - mid.y), 2.0 * double(hit.z - mid.z), 1.0);
        const double rhs = double(dot(hit - mid, hit - mid));
        A += row * row.transpose();
        b += row * rhs;
        ++used;
    }
    if (used < 16) {
        throw InvalidGeometry("cranium: only " + std::to_string(used) + " of " + std::to_string(kRays) +
                              " rays towards the hairline's centroid met the scalp inside the hairline (16 needed): check the hairline belongs to this scalp");
    }
    const Eigen::Vector4d x = A.ldlt().solve(b);
    const double r2 = x[3] + x.head<3>().squaredNorm();
    if (!std::isfinite(r2) || !(r2 > 0.0)) throw InvalidGeometry("cranium: the scalp inside the hairline fits no sphere");
    Cranium c;
    c.center = mid + float3(float(x[0]), float(x[1]), float(x[2]));
    c.radius = float(std::sqrt(r2));
    c.samples = used;
    return c;
}

}  // namespace groom
