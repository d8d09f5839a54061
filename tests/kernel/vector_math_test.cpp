// kernel/math/vector_math.h against the double-precision closed forms, and the property the curl op
// relies on for thread-count independence: a value does not depend on the batch it came in.
#include "kernel/math/vector_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

namespace groom {
namespace {

/// Angles over many turns, both signs, dense enough to hit every quadrant's neighbourhood.
std::vector<float> angles()
{
    std::vector<float> a;
    for (int i = -20000; i <= 20000; ++i) a.push_back(0.00157f * float(i));
    a.push_back(0.0f);
    a.push_back(-0.0f);
    a.push_back(1e4f);
    return a;
}

TEST(VectorMath, SinCosWithinAFewUlpOfTheTrueValues)
{
    const std::vector<float> a = angles();
    std::vector<float> s(a.size()), c(a.size()), c2(a.size());
    sin_cos(a.data(), a.size(), s.data(), c.data());
    cos_of(a.data(), a.size(), c2.data());
    for (size_t i = 0; i < a.size(); ++i) {
        // 4 ulp of a value of size 1 (libmvec's documented bound) is 4.8e-7; the difference is
        // absolute because near a zero of sin the true value is tiny and the argument's own float
        // rounding dominates.
        EXPECT_NEAR(s[i], std::sin(double(a[i])), 5e-7) << a[i];
        EXPECT_NEAR(c[i], std::cos(double(a[i])), 5e-7) << a[i];
        EXPECT_EQ(std::memcmp(&c[i], &c2[i], sizeof(float)), 0) << "cos_of differs from sin_cos's cosine at " << a[i];
    }
}

TEST(VectorMath, PowWithinAFewUlpOfTheTrueValues)
{
    for (const float e : {0.02f, 0.5f, 1.0f, 0.8f, 4.0f, 40.0f}) {
        std::vector<float> x, y;
        for (int i = 0; i <= 1000; ++i) x.push_back(float(i) / 1000.0f);
        y.resize(x.size());
        pow_of(x.data(), e, x.size(), y.data());
        for (size_t i = 0; i < x.size(); ++i) {
            const double want = std::pow(double(x[i]), double(e));
            EXPECT_NEAR(y[i], want, 1e-6 * std::max(want, 1e-30) + 1e-38) << x[i] << "^" << e;
        }
    }
}

TEST(VectorMath, AValueDoesNotDependOnItsBatch)
{
    const std::vector<float> a = angles();
    std::vector<float> s(a.size()), c(a.size());
    sin_cos(a.data(), a.size(), s.data(), c.data());
    // Every start and length up to 9 (whole registers, partial ones, each lane position).
    for (size_t start = 0; start < 4000; start += 7) {
        for (size_t n = 1; n <= 9 && start + n <= a.size(); ++n) {
            float bs[9], bc[9];
            sin_cos(a.data() + start, n, bs, bc);
            for (size_t i = 0; i < n; ++i) {
                ASSERT_EQ(std::memcmp(&bs[i], &s[start + i], sizeof(float)), 0) << "sin at " << start + i << " in a batch of " << n;
                ASSERT_EQ(std::memcmp(&bc[i], &c[start + i], sizeof(float)), 0) << "cos at " << start + i << " in a batch of " << n;
            }
        }
    }
}

}  // namespace
}  // namespace groom
