// Benchmarks for `groom partition` (talk, Sec. 2.2): a 30-guide cornrow layout over a real head
// (Sintel's bust, ../shared/datasets, CC BY), or over an exact sphere of the same size when the
// datasets are absent. The scalp is built once outside the timed loops.
#include "fields/scalp_field.h"
#include "kernel/math/polyline.h"
#include "kernel/parallel.h"
#include "ops/partition.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

using namespace groom;

namespace {

/// `../shared/datasets/<relative>` beside the source tree (or under $GROOM_SHARED_DATASETS), empty
/// when absent.
std::string shared_file(const std::string& relative)
{
    const char* env = std::getenv("GROOM_SHARED_DATASETS");
    const std::filesystem::path root = env ? std::filesystem::path(env) : std::filesystem::path(GROOM_SOURCE_DIR) / ".." / "shared" / "datasets";
    const std::filesystem::path p = root / relative;
    return std::filesystem::exists(p) ? p.string() : std::string();
}

struct Layout {
    std::shared_ptr<const Surface> scalp;
    CurveSet guides;
    std::string what;
};

/// 30 cornrow guides from the hairline over the crown to the nape, 64 points each, lying 3 mm
/// above the scalp: row k lies in the plane through the head centre tilted 60 degrees left to
/// right, each point where the ray from the centre meets the scalp.
const Layout& cornrows()
{
    static const Layout layout = [] {
        Layout l;
        const std::string head = shared_file("sintel_frostbitten/sintel.obj");
        float3 centre(0.0f, 1.50f, 0.01f);  // Sintel's cranium, metres, +Y up, facing +Z
        float reach = 0.5f;
        if (!head.empty()) {
            l.scalp = load_scalp(head);
            l.what = "sintel.obj";
        }
        else {
            l.scalp = std::make_shared<AnalyticSphere>(centre, 0.12f);
            l.what = "sphere (../shared/datasets absent)";
        }
        const int rows = 30, points = 64;
        std::vector<int64_t> counts(rows, points);
        l.guides = CurveSet::from_counts(counts);
        auto P = l.guides.positions_for_write();
        for (int k = 0; k < rows; ++k) {
            const float phi = (-60.0f + 120.0f * k / (rows - 1)) * float(M_PI / 180.0);
            for (int i = 0; i < points; ++i) {
                const float theta = (25.0f + 125.0f * i / (points - 1)) * float(M_PI / 180.0);
                const float3 d(std::sin(theta) * std::sin(phi), std::sin(theta) * std::cos(phi), std::cos(theta));
                float3 hit;
                if (!l.scalp->first_intersection(centre + d * reach, centre, hit)) hit = l.scalp->closest_point(centre + d * reach);
                P[l.guides.points_of(k).begin + i] = hit + l.scalp->normal(hit) * 0.003f;
            }
        }
        return l;
    }();
    return layout;
}

void BM_FindAdjacent(benchmark::State& state)
{
    const Layout& l = cornrows();
    ThreadLimit limit(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(find_adjacent_guides(l.guides, *l.scalp));
    state.SetLabel(l.what);
}

void BM_Partition(benchmark::State& state)
{
    const Layout& l = cornrows();
    ThreadLimit limit(int(state.range(0)));
    PartitionParams params;
    params.count = 48;
    params.samples = 12;
    params.widths.root = params.widths.tip = 0.0005f;
    int64_t segments = 0;
    for (auto _ : state) {
        const CurveSet out = partition(l.guides, *l.scalp, params);
        segments = int64_t(out.num_curves());
        benchmark::DoNotOptimize(out.positions().data());
    }
    state.counters["segments"] = double(segments);
    state.counters["segments/s"] = benchmark::Counter(double(segments), benchmark::Counter::kIsIterationInvariantRate);
    state.SetLabel(l.what);
}

}  // namespace

BENCHMARK(BM_FindAdjacent)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Partition)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
