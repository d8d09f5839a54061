// Edges (baby hairs) along the default hairline of the synthetic head (ops/head.h, what `groom head`
// writes), the scalp field and the hairline built once, outside the timing. The op's cost is one
// walk on the scalp per hair: a closest-point query per point.
#include "fields/scalp_field.h"
#include "ops/edges.h"
#include "ops/hairline.h"
#include "ops/head.h"

#include <benchmark/benchmark.h>

#include <memory>

using namespace groom;

namespace {

struct Scene {
    std::unique_ptr<ScalpField> scalp;
    CurveSet hairline;
};

const Scene& scene()
{
    static const Scene sc = [] {
        Scene s;
        s.scalp = std::make_unique<ScalpField>(build_scalp(make_head(HeadParams{})));
        s.hairline = make_hairline(*s.scalp, s.scalp->bounds(), HairlineParams{});
        return s;
    }();
    return sc;
}

void run(benchmark::State& state, const EdgesParams& params)
{
    const Scene& s = scene();
    size_t hairs = 0, points = 0;
    for (auto _ : state) {
        const CurveSet cs = edges(*s.scalp, s.hairline, params);
        hairs = cs.num_curves();
        points = cs.num_points();
        benchmark::DoNotOptimize(cs.positions().data());
    }
    state.counters["hairs"] = double(hairs);
    state.counters["points"] = double(points);
    state.counters["hairs/s"] = benchmark::Counter(double(hairs), benchmark::Counter::kIsIterationInvariantRate);
}

/// `groom edges --scalp head.vdb` as it runs with no options: forehead, temples and sideburns.
void BM_EdgesDefaults(benchmark::State& state) { run(state, EdgesParams{}); }

/// A dense fringe all round the head: 20,000 hairs from the nape round to the nape.
void BM_EdgesAllRound20k(benchmark::State& state)
{
    EdgesParams p;
    p.from = -180.0f;
    p.to = 180.0f;
    p.count = 20000;
    run(state, p);
}

}  // namespace

BENCHMARK(BM_EdgesDefaults)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EdgesAllRound20k)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
