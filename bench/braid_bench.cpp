// Braid speed: a cornrow groom (20 guides x 3 strands x 200 fibers x 64 samples, --orient scalp,
// clearance) on Sintel's head from ../shared/datasets (CC BY, Blender Foundation), converted by
// load_scalp; on an exact sphere of the same size when the datasets are absent, and always on the
// sphere too, as the reference for what the level-set queries cost. Reports strands/s and fibers/s.
#include "fields/scalp_field.h"
#include "kernel/parallel.h"
#include "ops/braid.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

using namespace groom;

namespace {

// Sintel's head (metres, +Y up): the skull's top is near (0, 1.655, 0); rows are arcs about this centre.
const float3 kHeadCentre(0.0f, 1.55f, 0.0f);
constexpr float kHeadRadius = 0.1f;

std::string sintel_path()
{
    const auto p = std::filesystem::path(GROOM_SOURCE_DIR) / ".." / "shared" / "datasets" / "sintel_frostbitten" / "sintel.obj";
    return std::filesystem::exists(p) ? p.string() : std::string();
}

/// 20 cornrow guides running front (forehead, +Z) to back over the head, side by side, each 64
/// points projected onto the scalp.
CurveSet cornrow_guides(const Surface& scalp)
{
    const int rows = 20, points = 64;
    std::vector<int64_t> counts(rows, points);
    CurveSet guides = CurveSet::from_counts(counts);
    auto P = guides.positions_for_write();
    for (int g = 0; g < rows; ++g) {
        const double phi = (-55.0 + 110.0 * g / (rows - 1)) * std::numbers::pi / 180.0;
        for (int k = 0; k < points; ++k) {
            const double th = (60.0 - 160.0 * k / (points - 1)) * std::numbers::pi / 180.0;
            const float3 d(float(std::sin(phi)), float(std::cos(phi) * std::cos(th)), float(std::cos(phi) * std::sin(th)));
            P[g * points + k] = scalp.closest_point(kHeadCentre + d * (2.0f * kHeadRadius));
        }
    }
    return guides;
}

BraidParams cornrow_params(int fibers)
{
    BraidParams p;
    p.strands = 3;
    p.samples = 64;
    p.frequency = 4.0f;  // 16 samples per knot
    p.width = 0.006f;    // 6 mm
    p.height = 0.003f;
    p.orient = BraidOrient::Scalp;
    p.clearance = 0.0005f;
    p.fibers = fibers;
    p.seed = 1;
    return p;
}

struct Scene {
    std::shared_ptr<const Surface> scalp;
    CurveSet guides;
};

const Scene& head_scene()
{
    static const Scene scene = [] {
        Scene s;
        const std::string path = sintel_path();
        if (path.empty()) s.scalp = std::make_shared<AnalyticSphere>(kHeadCentre, kHeadRadius);
        else s.scalp = load_scalp(path);
        s.guides = cornrow_guides(*s.scalp);
        return s;
    }();
    return scene;
}

const Scene& sphere_scene()
{
    static const Scene scene = [] {
        Scene s;
        s.scalp = std::make_shared<AnalyticSphere>(kHeadCentre, kHeadRadius);
        s.guides = cornrow_guides(*s.scalp);
        return s;
    }();
    return scene;
}

void run(benchmark::State& state, const Scene& scene, int fibers)
{
    const ThreadLimit limit(int(state.range(0)));
    const BraidParams params = cornrow_params(fibers);
    int64_t points = 0;
    for (auto _ : state) {
        BraidResult r = braid(scene.guides, params, scene.scalp.get());
        points = r.report.points;
        benchmark::DoNotOptimize(r.curves.positions().data());
    }
    const double strands = double(scene.guides.num_curves()) * params.strands;
    state.counters["strands/s"] = benchmark::Counter(strands, benchmark::Counter::kIsIterationInvariantRate);
    if (fibers > 0) state.counters["fibers/s"] = benchmark::Counter(strands * fibers, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["points"] = double(points);
}

void BM_CornrowsHead(benchmark::State& state)
{
    state.SetLabel(sintel_path().empty() ? "sphere (datasets absent)" : "sintel.obj level set");
    run(state, head_scene(), 200);
}
void BM_CornrowsSphere(benchmark::State& state) { run(state, sphere_scene(), 200); }
void BM_CornrowStrandsHead(benchmark::State& state) { run(state, head_scene(), 0); }

}  // namespace

BENCHMARK(BM_CornrowsHead)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CornrowsSphere)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CornrowStrandsHead)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
