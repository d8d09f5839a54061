// The knot distribution of braid (declared in ops/braid.h): the alpha remap (knot bias and density),
// knots per guide, the woven fraction t_b and the knot centres that `groom partition --centroids
// knots` shares.
#include "ops/braid.h"

#include "kernel/error.h"
#include "kernel/math/spline.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace groom {

namespace {

/// Intervals of the knot-density table: fine enough that the piecewise-linear alpha is within
/// ~1e-7 of the exact integral for any spline of a few dozen values.
constexpr int kDensityTable = 4096;

}  // namespace

KnotRemap::KnotRemap(const BraidParams& params)
{
    // Schlick's bias curve x / ((1/g - 2)(1 - x) + 1) with g = (1 - b) / 2: smooth, monotonic, slope
    // g/(1-g) at the root and (1-g)/g at the tip, identity at b = 0.
    bias_k_ = 2.0 * double(params.knot_bias) / (1.0 - double(params.knot_bias));
    if (!params.knot_density.empty()) {
        // alpha' proportional to the density spline: integrate it (Simpson per interval) into a table.
        // Catmull-Rom can undershoot between positive values; a floor keeps alpha strictly increasing.
        const float lowest = *std::min_element(params.knot_density.begin(), params.knot_density.end());
        const auto density = [&](double t) {
            return std::max(double(sample_uniform_spline(params.knot_density, float(t))), 1e-3 * lowest);
        };
        density_.assign(kDensityTable + 1, 0.0);
        for (int j = 0; j < kDensityTable; ++j) {
            const double a = double(j) / kDensityTable, b = double(j + 1) / kDensityTable;
            density_[j + 1] = density_[j] + (b - a) / 6.0 * (density(a) + 4.0 * density(0.5 * (a + b)) + density(b));
        }
        const double total = density_.back();
        for (double& v : density_) v /= total;
        density_.back() = 1.0;
    }
    if (!identity()) {
        double prev = 0.0;
        max_slope_ = 0.0;
        for (int j = 1; j <= kDensityTable; ++j) {
            const double a = alpha(double(j) / kDensityTable);
            max_slope_ = std::max(max_slope_, (a - prev) * kDensityTable);
            prev = a;
        }
        // The bias curve is steepest at an end; the secant above slightly underestimates it there.
        if (density_.empty()) max_slope_ = std::max(1.0 / (bias_k_ + 1.0), bias_k_ + 1.0);
    }
}

double KnotRemap::density_alpha(double t) const
{
    if (density_.empty()) return t;
    const double x = t * kDensityTable;
    const int j = std::min(int(x), kDensityTable - 1);
    return density_[j] + (density_[j + 1] - density_[j]) * (x - j);
}

double KnotRemap::density_inverse(double a) const
{
    if (density_.empty()) return a;
    const size_t hi = std::clamp<size_t>(std::upper_bound(density_.begin(), density_.end(), a) - density_.begin(), 1,
                                         density_.size() - 1);
    const size_t lo = hi - 1;
    const double seg = density_[hi] - density_[lo];
    return (double(lo) + (seg > 0.0 ? (a - density_[lo]) / seg : 0.0)) / kDensityTable;
}

double KnotRemap::alpha(double t) const
{
    t = std::clamp(t, 0.0, 1.0);
    const double x = density_alpha(t);
    return bias_k_ == 0.0 ? x : x / (bias_k_ * (1.0 - x) + 1.0);
}

double KnotRemap::inverse(double a) const
{
    a = std::clamp(a, 0.0, 1.0);
    const double x = bias_k_ == 0.0 ? a : a * (bias_k_ + 1.0) / (1.0 + a * bias_k_);
    return density_inverse(std::clamp(x, 0.0, 1.0));
}

double braid_frequency(const BraidParams& params, double guide_length)
{
    if (params.frequency) return *params.frequency;
    if (params.knot_length) return std::max(guide_length - double(params.loose_length), 0.0) / *params.knot_length;
    return BraidParams::kDefaultFrequency;
}

double braid_woven_fraction(const BraidParams& params, double guide_length)
{
    if (!(params.loose_length > 0.0f) || !(guide_length > 0.0)) return 1.0;
    return std::clamp(1.0 - double(params.loose_length) / guide_length, 0.0, 1.0);
}

std::vector<float> braid_knot_parameters(const BraidParams& params, double guide_length)
{
    params.validate();
    const double F = braid_frequency(params, guide_length);
    if (F > 1e8) {
        throw LimitExceeded("braid: " + format_number(F) + " knots on one guide is more than 1e8; raise `knot_length` or lower `frequency`");
    }
    const KnotRemap remap(params);
    std::vector<float> t;
    const double woven = braid_woven_fraction(params, guide_length);
    for (int64_t k = 0; (double(k) + 0.5) <= F; ++k) t.push_back(float(woven * remap.inverse((double(k) + 0.5) / F)));
    return t;
}

}  // namespace groom
