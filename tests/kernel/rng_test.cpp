#include "kernel/rng.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace groom;

TEST(Rng, SameKeyGivesSameStreamAndDrawsAreCounterBased)
{
    Rng a(42, 7, 1), b(42, 7, 1);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next_u64(), b.next_u64());
    Rng c(42, 7, 1);
    EXPECT_EQ(c.at(57), Rng(42, 7, 1).at(57));  // no state needed to reach value 57
    EXPECT_NE(Rng(42, 7, 1).at(0), Rng(42, 8, 1).at(0));
    EXPECT_NE(Rng(42, 7, 1).at(0), Rng(43, 7, 1).at(0));
    EXPECT_NE(Rng(42, 7, 1).at(0), Rng(42, 7, 2).at(0));
}

TEST(Rng, UniformMeanAndVarianceWithinThreeSigma)
{
    const int n = 200000;
    double sum = 0.0, sum2 = 0.0;
    for (int id = 0; id < n; ++id) {
        const double u = Rng(1, id).uniform();
        ASSERT_GE(u, 0.0);
        ASSERT_LT(u, 1.0);
        sum += u;
        sum2 += u * u;
    }
    const double mean = sum / n, var = sum2 / n - mean * mean;
    EXPECT_NEAR(mean, 0.5, 3.0 * std::sqrt(1.0 / 12.0 / n));
    EXPECT_NEAR(var, 1.0 / 12.0, 0.002);
}

TEST(Rng, BelowCoversRangeUniformly)
{
    Rng r(3, 4);
    int counts[5] = {};
    const int n = 50000;
    for (int i = 0; i < n; ++i) {
        const uint32_t k = r.below(5);
        ASSERT_LT(k, 5u);
        ++counts[k];
    }
    const double p = 0.2, sigma = std::sqrt(n * p * (1 - p));
    for (int c : counts) EXPECT_NEAR(c, n * p, 4.0 * sigma);
}

TEST(Rng, DiscIsAreaUniform)
{
    Rng r(9, 9);
    int inner = 0;
    const int n = 40000;
    for (int i = 0; i < n; ++i) {
        float x, y;
        r.disc(x, y);
        ASSERT_LE(x * x + y * y, 1.0f + 1e-6f);
        inner += (x * x + y * y) < 0.25f;  // radius 1/2 holds a quarter of the area
    }
    EXPECT_NEAR(inner, n * 0.25, 4.0 * std::sqrt(n * 0.25 * 0.75));
}
