// A two-puff groom (Izzy's, talk Sec. 3.2): 2 x 20,000 curled hairs on a real head scan
// (../shared/datasets/lee_perry_smith, closed, ~8.6 units wide), or on the synthetic head
// (ops/head.h) when the shared datasets are absent. The scalp field is built once, outside the timing.
// Measured in stages, so the split between guides, centreline interpolation (generate) and the curl
// op, which is the reference cost every curled groom pays, shows in the same run.
#include "fields/keep_outside.h"
#include "fields/scalp_field.h"
#include "kernel/io/mesh_io.h"
#include "ops/curl.h"
#include "ops/generate.h"
#include "ops/head.h"
#include "ops/puff.h"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

using namespace groom;

namespace {

constexpr int64_t kHairsPerPuff = 20000;

struct Scene {
    std::unique_ptr<ScalpField> scalp;
    std::string head;
    PuffParams left, right;
};

const Scene& scene()
{
    static const Scene sc = [] {
        Scene s;
        const std::filesystem::path real = std::filesystem::path(GROOM_SOURCE_DIR) / ".." / "shared" / "datasets" /
                                           "lee_perry_smith" / "LeePerrySmith.obj";
        PolygonSoup soup;
        if (std::filesystem::exists(real)) {
            soup = read_mesh(real.string());
            s.head = "LeePerrySmith.obj";
        }
        else {
            soup = make_head({});
            s.head = "synthetic head (../shared/datasets absent)";
        }
        s.scalp = std::make_unique<ScalpField>(build_scalp(soup));
        Bounds3 box;
        for (const float3& p : soup.points) box.extend(p);
        const float3 size = box.size();
        // Two puffs on the crown, left and right of the midline, as Izzy wears them.
        for (int side : {-1, 1}) {
            PuffParams p;
            const float3 q(box.center().x + side * 0.22f * size.x, box.hi.y + 0.2f * size.y, box.center().z - 0.1f * size.z);
            const float3 c0 = s.scalp->closest_point(q);
            p.center = c0;
            p.radius = 0.12f * size.x;
            p.sphere_radius = 0.25f * size.x;
            p.sphere_center = c0 + s.scalp->normal(c0) * (0.75f * p.sphere_radius);
            p.rows = p.cols = 6;
            p.cap_angle = 100.0f;
            p.hairs = kHairsPerPuff;
            p.curl.hair_type = "4a";
            p.curl.units_per_cm = size.x / 16.0f;  // a head is about 16 cm wide
            p.curl.seed = side > 0 ? 2 : 1;
            p.first_id = side > 0 ? 100000 : 0;
            (side < 0 ? s.left : s.right) = p;
        }
        return s;
    }();
    return sc;
}

void BM_TwoPuffs(benchmark::State& state)
{
    const Scene& s = scene();
    size_t points = 0;
    for (auto _ : state) {
        points = 0;
        for (const PuffParams* p : {&s.left, &s.right}) {
            const PuffResult r = puff(*s.scalp, scalp_root_sampler(*s.scalp), *p);
            points += r.hairs.num_points() + r.guides.num_points();
            benchmark::DoNotOptimize(r.hairs.positions().data());
        }
    }
    state.SetLabel(s.head);
    state.counters["hairs"] = double(2 * kHairsPerPuff);
    state.counters["points"] = double(points);
    state.SetItemsProcessed(int64_t(state.iterations()) * 2 * kHairsPerPuff);
}

// Without the curl: guides plus interpolated centrelines (scatter, kd-tree, blend, cull).
void BM_TwoPuffsCentrelinesOnly(benchmark::State& state)
{
    const Scene& s = scene();
    for (auto _ : state) {
        for (const PuffParams* p : {&s.left, &s.right}) {
            const CurveSet guides = puff_guides(*s.scalp, *p);
            GenerateParams g;
            g.count = p->hairs;
            g.points = p->hair_points;
            g.region_center = s.scalp->closest_point(p->center);
            g.region_radius = p->radius;
            const CurveSet c = generate(guides, *s.scalp, scalp_root_sampler(*s.scalp), g);
            benchmark::DoNotOptimize(c.positions().data());
        }
    }
    state.SetLabel(s.head);
    state.SetItemsProcessed(int64_t(state.iterations()) * 2 * kHairsPerPuff);
}

// The curl step alone on the two puffs' centrelines, two ways to keep hairs out of the head: the
// curl op's own scalp check (every point queried; the reference) against what puff does (curl
// freely, then keep_outside on the curves, which skips points provably outside).
const std::vector<CurveSet>& centrelines()
{
    static const std::vector<CurveSet> c = [] {
        const Scene& s = scene();
        std::vector<CurveSet> out;
        for (const PuffParams* p : {&s.left, &s.right}) {
            GenerateParams g;
            g.count = p->hairs;
            g.points = p->hair_points;
            g.region_center = s.scalp->closest_point(p->center);
            g.region_radius = p->radius;
            out.push_back(generate(puff_guides(*s.scalp, *p), *s.scalp, scalp_root_sampler(*s.scalp), g));
        }
        return out;
    }();
    return c;
}

void curl_step(benchmark::State& state, bool op_checks_scalp)
{
    const Scene& s = scene();
    const std::vector<CurveSet>& c = centrelines();
    size_t points = 0;
    for (auto _ : state) {
        points = 0;
        for (int k = 0; k < 2; ++k) {
            CurlParams p = (k == 0 ? s.left : s.right).curl;
            p.preserve_length = false;
            CurveSet out = curl(c[k], p, op_checks_scalp ? s.scalp.get() : nullptr);
            if (!op_checks_scalp) keep_outside(out, *s.scalp, KeepOutside{});
            points += out.num_points();
            benchmark::DoNotOptimize(out.positions().data());
        }
    }
    state.SetLabel(s.head);
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(points));
}

void BM_CurlStepOpScalpCheck(benchmark::State& state) { curl_step(state, true); }
void BM_CurlStepThenPushOut(benchmark::State& state) { curl_step(state, false); }

void BM_TwoPuffsGuidesOnly(benchmark::State& state)
{
    const Scene& s = scene();
    for (auto _ : state) {
        for (const PuffParams* p : {&s.left, &s.right}) benchmark::DoNotOptimize(puff_guides(*s.scalp, *p).positions().data());
    }
    state.SetLabel(s.head);
}

}  // namespace

BENCHMARK(BM_TwoPuffs)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TwoPuffsCentrelinesOnly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CurlStepOpScalpCheck)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CurlStepThenPushOut)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TwoPuffsGuidesOnly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
