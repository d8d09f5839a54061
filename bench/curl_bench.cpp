// Curled points per second for 100,000 hairs x 128 output points, against the floor: a plain
// circular helix of the same size (no shapes, no blending, no frames, no length preservation).
#include "kernel/parallel.h"
#include "ops/curl.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

using namespace groom;

namespace {

constexpr int kHairs = 100000;
constexpr int kGuidePoints = 32;
constexpr float kLength = 10.0f;
// 10.06 units (the guides are gently bent) x 0.785 cycles/unit x 16 samples/cycle
// -> ceil(126.3) + 1 = 128 output points per hair.
constexpr float kFrequency = 0.785f;
constexpr int kOutPoints = 128;

const CurveSet& guides()
{
    static const CurveSet cs = [] {
        CurveSet g = CurveSet::from_counts(std::vector<int64_t>(kHairs, kGuidePoints));
        auto P = g.positions_for_write();
        for (int c = 0; c < kHairs; ++c) {
            const float x = float(c % 316), z = float(c / 316);
            for (int i = 0; i < kGuidePoints; ++i) {
                const float s = kLength * float(i) / float(kGuidePoints - 1);
                P[size_t(c) * kGuidePoints + size_t(i)] = {x + 0.5f * std::sin(0.3f * s), s, z};  // gently bent
            }
        }
        return g;
    }();
    return cs;
}

void run_curl(benchmark::State& state, CurlParams p)
{
    const CurveSet& g = guides();
    p.frequency = {kFrequency, kFrequency};
    p.amplitude = {0.2f, 0.3f};
    size_t points = 0;
    for (auto _ : state) {
        CurveSet out = curl(g, p);
        points = out.num_points();
        benchmark::DoNotOptimize(out.positions().data());
    }
    state.counters["points_per_hair"] = double(points) / kHairs;
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(points));
}

void BM_CurlMixedShapes(benchmark::State& state)
{
    CurlParams p;  // type 3a, uniformity 0.7: every shape appears
    run_curl(state, p);
}

void BM_CurlCirclesOnly(benchmark::State& state)
{
    CurlParams p;
    p.dominant = kCircle;
    p.uniformity = 1.0f;
    run_curl(state, p);
}

// The floor: x = A cos(2 pi F s), z = A sin(2 pi F s) around a straight +Y guide, written into a
// CurveSet of the same size with the same parallel loop.
void BM_HelixFloor(benchmark::State& state)
{
    const CurveSet& g = guides();
    const auto in = g.positions();
    for (auto _ : state) {
        CurveSet out = CurveSet::from_counts(std::vector<int64_t>(kHairs, kOutPoints));
        auto P = out.positions_for_write();
        parallel_for(kHairs, 64, [&](int64_t b, int64_t e) {
            for (int64_t c = b; c < e; ++c) {
                const float3 root = in[size_t(c) * kGuidePoints];
                for (int i = 0; i < kOutPoints; ++i) {
                    const float s = kLength * float(i) / float(kOutPoints - 1);
                    const float a = 2.0f * std::numbers::pi_v<float> * kFrequency * s;
                    P[size_t(c) * kOutPoints + size_t(i)] = root + float3(0.25f * std::cos(a), s, 0.25f * std::sin(a));
                }
            }
        });
        benchmark::DoNotOptimize(P.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * kHairs * kOutPoints);
}

}  // namespace

BENCHMARK(BM_HelixFloor)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CurlCirclesOnly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CurlMixedShapes)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
