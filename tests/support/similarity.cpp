#include "support/similarity.h"

#include "kernel/rng.h"

#include <cmath>

namespace groom {

Similarity Similarity::random(uint64_t seed, double min_scale, double max_scale, double max_offset)
{
    Rng rng(seed, 0);
    // A uniform unit quaternion (Shoemake 1992) gives a uniformly random rotation.
    const double u1 = rng.uniform_double(), u2 = rng.uniform_double() * 2.0 * M_PI, u3 = rng.uniform_double() * 2.0 * M_PI;
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    const double w = a * std::sin(u2), x = a * std::cos(u2), y = b * std::sin(u3), z = b * std::cos(u3);
    Similarity s;
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s.rotation[i][j] = r[i][j];
    s.scale = std::exp(std::log(min_scale) + rng.uniform_double() * (std::log(max_scale) - std::log(min_scale)));
    for (double& t : s.translation) t = (rng.uniform_double() * 2.0 - 1.0) * max_offset * s.scale;
    return s;
}

float3 Similarity::apply(const float3& p) const
{
    const double v[3] = {p.x, p.y, p.z};
    double o[3];
    for (int i = 0; i < 3; ++i) o[i] = scale * (rotation[i][0] * v[0] + rotation[i][1] * v[1] + rotation[i][2] * v[2]) + translation[i];
    return float3(float(o[0]), float(o[1]), float(o[2]));
}

float3 Similarity::apply_direction(const float3& d) const
{
    const double v[3] = {d.x, d.y, d.z};
    double o[3];
    for (int i = 0; i < 3; ++i) o[i] = rotation[i][0] * v[0] + rotation[i][1] * v[1] + rotation[i][2] * v[2];
    return float3(float(o[0]), float(o[1]), float(o[2]));
}

float3 Similarity::inverse_direction(const float3& d) const
{
    const double v[3] = {d.x, d.y, d.z};
    double o[3];
    for (int i = 0; i < 3; ++i) o[i] = rotation[0][i] * v[0] + rotation[1][i] * v[1] + rotation[2][i] * v[2];
    return float3(float(o[0]), float(o[1]), float(o[2]));
}

PolygonSoup Similarity::apply(const PolygonSoup& soup) const
{
    PolygonSoup out = soup;
    for (float3& p : out.points) p = apply(p);
    return out;
}

}  // namespace groom
