// Render time for a 100k-curve groom (32 points each) on the default head at 1024x1024, by
// supersampling factor and thread count, plus the head alone (the mesh cost).
#include "kernel/parallel.h"
#include "kernel/rng.h"
#include "ops/head.h"
#include "ops/render.h"

#include <benchmark/benchmark.h>

using namespace groom;

namespace {

/// Hairs rooted at upper head vertices, leaving along the vertex direction from the head's centre
/// and bending down under gravity: a bob of 100k curves, enough overlap to stress the depth test.
CurveSet make_groom(const PolygonSoup& head, int64_t curves, int points)
{
    std::vector<int64_t> counts(size_t(curves), points);
    CurveSet c = CurveSet::from_counts(counts);
    auto P = c.positions_for_write();
    auto width = c.add<float>(Domain::Point, attr::width);
    std::vector<float3> roots;
    for (const float3& p : head.points)
        if (p.y > 2.0f) roots.push_back(p);
    parallel_for(curves, 1024, [&](int64_t b, int64_t e) {
        for (int64_t i = b; i < e; ++i) {
            Rng rng(7, uint64_t(i));
            const float3 root = roots[rng.below(uint32_t(roots.size()))] + float3(rng.uniform(-0.3f, 0.3f), 0, rng.uniform(-0.3f, 0.3f));
            float3 dir = normalize(root - float3(0, 2, -1));
            float3 p = root;
            for (int k = 0; k < points; ++k) {
                P[i * points + k] = p;
                width[i * points + k] = 0.008f;
                dir = normalize(dir + float3(0, -0.12f, 0));
                p = p + dir * 0.6f;
            }
        }
    });
    return c;
}

const PolygonSoup& head()
{
    static const PolygonSoup h = make_head(HeadParams{});
    return h;
}

void BM_RenderGroom(benchmark::State& state)
{
    static const CurveSet groom = make_groom(head(), 100000, 32);
    RenderScene scene;
    scene.mesh = &head();
    scene.curves = {&groom};
    RenderParams p;
    p.supersample = int(state.range(0));
    ThreadLimit limit(int(state.range(1)));
    for (auto _ : state) benchmark::DoNotOptimize(render(scene, view_camera(View::ThreeQuarter), p));
    state.counters["curves/s"] = benchmark::Counter(double(groom.num_curves()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderGroom)->ArgsProduct({{2, 3}, {1, 2}})->ArgNames({"ss", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RenderHeadOnly(benchmark::State& state)
{
    RenderScene scene;
    scene.mesh = &head();
    RenderParams p;
    p.supersample = 3;
    ThreadLimit limit(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(render(scene, view_camera(View::ThreeQuarter), p));
}
BENCHMARK(BM_RenderHeadOnly)->Arg(1)->Arg(2)->ArgName("threads")->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
