// Izzy's whole scalp gathered into two puffs (ops/gather.h) on the synthetic head (ops/head.h), as the
// demo makes it: default hairline, centre parting, 12,000 gathered hairs. The reference in the same
// process is the puff op growing the same number of its own curled hairs (no path on the scalp), so
// the ratio says what the walk on the scalp and the longer hairs cost. The field is built outside the
// timing; the hairline and the parting are timed on their own.
#include "fields/scalp_field.h"
#include "fields/surface_path.h"
#include "ops/gather.h"
#include "ops/hairline.h"
#include "ops/head.h"
#include "ops/puff.h"

#include <benchmark/benchmark.h>

#include <memory>

using namespace groom;

namespace {

constexpr int64_t kHairs = 12000;

struct Scene {
    std::unique_ptr<ScalpField> scalp;
    CurveSet hairline, parting;
    PuffParams puff_params[2];
    std::vector<GatherPuff> puffs;
};

const Scene& scene()
{
    static const Scene sc = [] {
        Scene s;
        HeadParams hp;
        hp.resolution = 96;
        s.scalp = std::make_unique<ScalpField>(build_scalp(make_head(hp)));
        s.hairline = make_hairline(*s.scalp, s.scalp->bounds(), HairlineParams{});
        std::vector<float3> path;
        surface_path_through(*s.scalp, {{0, 8, 12}, {0, 14, -1}, {0, -2, -14}}, 0.25f, 0.0f, path);
        s.parting = CurveSet::from_counts(std::vector<int64_t>{int64_t(path.size())});
        std::copy(path.begin(), path.end(), s.parting.positions_for_write().begin());
        for (int side : {0, 1}) {
            const float x = side ? 4.8f : -4.8f;
            PuffParams& p = s.puff_params[side];
            p.center = {x, 9.5f, -1.5f};
            p.radius = 3.0f;
            p.sphere_center = {x * 7.5f / 4.8f, 14.0f, -1.5f};
            p.sphere_radius = 6.0f;
            p.rows = p.cols = 6;
            p.cap_angle = 160.0f;
            p.curl.hair_type = "4a";
            p.curl.seed = uint64_t(side + 1);
            p.hairs = kHairs / 2;
            GatherPuff g;
            g.guides = puff_guides(*s.scalp, p);
            g.base = g.guides.find<float3>(Domain::Detail, "puff_base")[0];
            g.base_radius = p.radius;
            g.sphere_center = p.sphere_center;
            g.sphere_radius = p.sphere_radius;
            s.puffs.push_back(std::move(g));
        }
        return s;
    }();
    return sc;
}

void BM_GatherIntoTwoPuffs(benchmark::State& state)
{
    const Scene& s = scene();
    const HairRegion region(*s.scalp, s.hairline, s.parting, HairRegionParams{});
    GatherParams params;
    params.hairs = kHairs;
    params.curl.hair_type = "4a";
    params.curl.seed = 3;
    size_t points = 0;
    for (auto _ : state) {
        const GatherResult r = gather(*s.scalp, scalp_root_sampler(*s.scalp), s.puffs, region, params);
        points = r.hairs.num_points();
        benchmark::DoNotOptimize(r.hairs.positions().data());
    }
    state.counters["hairs/s"] = benchmark::Counter(double(kHairs), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["points"] = double(points);
}

void BM_ReferencePuffHairs(benchmark::State& state)
{
    const Scene& s = scene();
    size_t points = 0;
    for (auto _ : state) {
        points = 0;
        for (const PuffParams& p : s.puff_params) {
            const PuffResult r = puff(*s.scalp, scalp_root_sampler(*s.scalp), p);
            points += r.hairs.num_points();
            benchmark::DoNotOptimize(r.hairs.positions().data());
        }
    }
    state.counters["hairs/s"] = benchmark::Counter(double(kHairs), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["points"] = double(points);
}

void BM_DefaultHairline(benchmark::State& state)
{
    const Scene& s = scene();
    for (auto _ : state) benchmark::DoNotOptimize(make_hairline(*s.scalp, s.scalp->bounds(), HairlineParams{}).positions().data());
}

}  // namespace

BENCHMARK(BM_GatherIntoTwoPuffs)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);
BENCHMARK(BM_ReferencePuffHairs)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);
BENCHMARK(BM_DefaultHairline)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
