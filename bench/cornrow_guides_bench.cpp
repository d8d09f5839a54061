// Cornrow guides (ops/cornrow_guides.h) from the hairline over the crown to the nape: on the
// synthetic head's scalp field with its default hairline (what `groom cornrow-guides --hairline`
// runs in the demo: straight-back rows walked on the scalp and spread along the nape), on an exact
// sphere with a circular hairline as the reference for what the level-set queries cost, and the
// cranium fit (ops/cranium.h) a head without --center/--radius gets. Scalp, hairline and region
// are built once, outside the timing. Arg: threads.
#include "fields/scalp_field.h"
#include "kernel/parallel.h"
#include "ops/cornrow_guides.h"
#include "ops/cranium.h"
#include "ops/hairline.h"
#include "ops/head.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <optional>

using namespace groom;

namespace {

struct Scene {
    std::shared_ptr<const Surface> scalp;
    std::optional<HairRegion> region;
};

const Scene& head_scene()
{
    static const Scene sc = [] {
        Scene s;
        auto field = std::make_shared<ScalpField>(build_scalp(make_head(HeadParams{})));
        const CurveSet hairline = make_hairline(*field, field->bounds(), HairlineParams{});
        s.region.emplace(*field, hairline, CurveSet(), HairRegionParams{});
        s.scalp = field;
        return s;
    }();
    return sc;
}

const Scene& sphere_scene()
{
    static const Scene sc = [] {
        Scene s;
        const float3 c(0.0f, 3.0f, -1.0f);
        auto sphere = std::make_shared<AnalyticSphere>(c, 10.0f);
        // A level circle 0.3 radii below the centre: the cap above it is the haired part.
        const int n = 720;
        CurveSet hairline = CurveSet::from_counts(std::vector<int64_t>{n});
        auto P = hairline.positions_for_write();
        const float r = std::sqrt(100.0f - 9.0f);
        for (int i = 0; i < n; ++i) {
            const float a = 2.0f * 3.14159265f * float(i) / float(n);
            P[size_t(i)] = c + float3(r * std::cos(a), -3.0f, r * std::sin(a));
        }
        s.region.emplace(*sphere, hairline, CurveSet(), HairRegionParams{});
        s.scalp = sphere;
        return s;
    }();
    return sc;
}

void run(benchmark::State& state, const Scene& s, int rows)
{
    const ThreadLimit limit(int(state.range(0)));
    CornrowGuidesParams p;
    p.count = rows;
    p.tail_length = 12.0f;
    size_t points = 0;
    for (auto _ : state) {
        const CornrowGuides g = cornrow_guides(*s.scalp, p, &*s.region);
        points = g.guides.num_points() + g.tails.num_points();
        benchmark::DoNotOptimize(g.guides.positions().data());
    }
    state.counters["points"] = double(points);
    state.counters["rows/s"] = benchmark::Counter(double(rows), benchmark::Counter::kIsIterationInvariantRate);
}

/// The demo's 12 rows with tails on the synthetic head's level set.
void BM_CornrowGuidesHead(benchmark::State& state) { run(state, head_scene(), 12); }
/// The same on an exact sphere of the default head's cranium.
void BM_CornrowGuidesSphere(benchmark::State& state) { run(state, sphere_scene(), 12); }

/// The cranium fitted inside the hairline (1,024 rays).
void BM_FitCraniumHead(benchmark::State& state)
{
    const Scene& s = head_scene();
    for (auto _ : state) benchmark::DoNotOptimize(fit_cranium(*s.scalp, *s.region, float3(0.0f, 1.0f, 0.0f)).radius);
}

}  // namespace

BENCHMARK(BM_CornrowGuidesHead)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CornrowGuidesSphere)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FitCraniumHead)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
