// `groom sections` on the demo's head (the synthetic head, centimetres, with groom hairline's default
// hairline): the box-braid grid the demo makes, with and without 20,000 roots, with floor-length
// guides, and the rows and radial layouts; the chart alone (SectionMap: rays onto the scalp and the
// cuts) shows how much of the cost is charting. The scalp field and the hairline are built once,
// outside the timings. BM_SectionsScan repeats the grid on the real head scan
// (../shared/datasets/lee_perry_smith) when it is there.
#include "fields/scalp_field.h"
#include "kernel/io/mesh_io.h"
#include "ops/hair_region.h"
#include "ops/hairline.h"
#include "ops/head.h"
#include "ops/section_map.h"
#include "ops/sections.h"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

using namespace groom;

namespace {

struct Scene {
    std::unique_ptr<ScalpField> scalp;
    CurveSet hairline;
    std::string label;
};

Scene make_scene(const PolygonSoup& soup, const std::string& label)
{
    Scene s;
    s.scalp = std::make_unique<ScalpField>(build_scalp(soup));
    s.hairline = make_hairline(*s.scalp, s.scalp->bounds(), HairlineParams{});
    s.label = label;
    return s;
}

const Scene& head()
{
    static const Scene s = make_scene(make_head({}), "synthetic head");
    return s;
}

const Scene* scan()
{
    static const std::unique_ptr<Scene> s = []() -> std::unique_ptr<Scene> {
        const std::filesystem::path real = std::filesystem::path(GROOM_SOURCE_DIR) / ".." / "shared" / "datasets" / "lee_perry_smith" /
                                           "LeePerrySmith.obj";
        if (!std::filesystem::exists(real)) return nullptr;
        return std::make_unique<Scene>(make_scene(read_mesh(real.string()), "LeePerrySmith.obj"));
    }();
    return s.get();
}

/// The demo's box braids: a grid of 8 bands, guides 24 cm long.
SectionsParams box_braids()
{
    SectionsParams p;
    p.length = 24.0f;
    return p;
}

void run(benchmark::State& state, const Scene& s, const SectionsParams& p)
{
    const RootSampler sampler = scalp_root_sampler(*s.scalp);
    size_t sections_made = 0, points = 0;
    for (auto _ : state) {
        const SectionsResult r = sections(*s.scalp, s.hairline, &sampler, p);
        sections_made = r.sections.size();
        points = r.guides.num_points() + r.partings.num_points() + r.roots.num_points();
        benchmark::DoNotOptimize(r.guides.positions().data());
    }
    state.SetLabel(s.label);
    state.counters["sections"] = double(sections_made);
    state.counters["points"] = double(points);
}

void BM_SectionsGrid(benchmark::State& state) { run(state, head(), box_braids()); }

void BM_SectionsGridWithRoots(benchmark::State& state)
{
    SectionsParams p = box_braids();
    p.roots = 20000;
    run(state, head(), p);
    state.SetItemsProcessed(int64_t(state.iterations()) * p.roots);
}

/// Floor-length braids: guides 150 cm long, a point every 0.25 cm, most of their march far below the
/// head, where a step needs only a bound of the distance (a closest-point search on the mesh there
/// made a fuzz input of 100,000-point guides take 32 s).
void BM_SectionsLongGuides(benchmark::State& state)
{
    SectionsParams p = box_braids();
    p.length = 150.0f;
    p.points = 600;
    run(state, head(), p);
}

void BM_SectionsRows(benchmark::State& state)
{
    SectionsParams p = box_braids();
    p.layout = SectionLayout::Rows;
    run(state, head(), p);
}

void BM_SectionsRadial(benchmark::State& state)
{
    SectionsParams p = box_braids();
    p.layout = SectionLayout::Radial;
    p.rings = 2;
    run(state, head(), p);
}

void BM_SectionMapOnly(benchmark::State& state)
{
    const Scene& s = head();
    const SectionsParams p = box_braids();
    HairRegionParams rp;
    const HairRegion region(*s.scalp, s.hairline, CurveSet(), rp);
    int64_t rays = 0;
    for (auto _ : state) {
        const SectionMap map(*s.scalp, s.hairline, region, p);
        rays = map.rays();
        benchmark::DoNotOptimize(map.sections().data());
    }
    state.SetLabel(s.label);
    state.counters["rays"] = double(rays);
    state.SetItemsProcessed(int64_t(state.iterations()) * rays);
}

void BM_SectionsScan(benchmark::State& state)
{
    const Scene* s = scan();
    if (!s) {
        state.SkipWithError("../shared/datasets/lee_perry_smith/LeePerrySmith.obj not found");
        return;
    }
    // The scan is in its own units (about 8.6 across the ears, a head 16 cm wide): lengths scaled.
    SectionsParams p;
    const float unit = 8.6f / 16.0f;
    p.length = 24.0f * unit;
    p.bend *= unit, p.clearance *= unit, p.layer *= unit, p.parting_gap *= unit, p.step *= unit;
    run(state, *s, p);
}

}  // namespace

BENCHMARK(BM_SectionsGrid)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SectionsGridWithRoots)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SectionsLongGuides)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SectionsRows)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SectionsRadial)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SectionMapOnly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SectionsScan)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
