// Exact area-uniform root sampling on an analytic sphere, for the generate and puff tests: the
// RootSampler a ScalpField gives the CLI, but on a surface whose measure is known in closed form.
#pragma once

#include "kernel/math/vec.h"
#include "kernel/rng.h"
#include "ops/generate.h"

#include <algorithm>
#include <cmath>

namespace groom::test {

/// Samples area-uniformly over the cap of the sphere (C, R) around the direction of the ball's
/// centre, `margin` times wider (in angle) than the cap the ball cuts, so that the sampler hands
/// generate() a strict superset of the ball, as a mesh sampler returning whole faces would.
inline RootSampler sphere_cap_sampler(const float3& C, float R, double margin = 1.3)
{
    return [=](const float3& center, float radius, int64_t count, uint64_t seed) {
        const float3 a = normalize(center - C, float3(0, 1, 0));
        const float3 e1 = any_perpendicular(a), e2 = cross(a, e1);
        // Largest angle from a of a sphere point within `radius` of the ball centre, bounded by pi.
        const double h = double(distance(center, C));
        double cos_max = -1.0;
        if (h > 0.0) cos_max = std::clamp((h * h + double(R) * R - double(radius) * radius) / (2.0 * h * R), -1.0, 1.0);
        const double theta = std::min(3.14159265358979, std::acos(cos_max) * margin);
        const double lo = std::cos(theta);
        std::vector<SurfaceSample> out(static_cast<size_t>(count));
        for (int64_t i = 0; i < count; ++i) {
            Rng rng(seed, uint64_t(i), 7);
            const double z = 1.0 - rng.uniform_double() * (1.0 - lo);  // cos(polar angle): uniform = area-uniform
            const double phi = 6.283185307179586 * rng.uniform_double();
            const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
            const float3 d = normalize(a * float(z) + e1 * float(s * std::cos(phi)) + e2 * float(s * std::sin(phi)));
            out[size_t(i)] = {C + d * R, d, -1};
        }
        return out;
    };
}

}  // namespace groom::test
