// Curve file throughput: read and write 10,000 curves x 32 points (320,000 points with a width,
// a float3 colour and a curve id) as .usda, binary .ply, ASCII .ply, .obj and .hair. Reported as
// points per second (items_per_second) and bytes per second. `usda_prims/N`: a .usda of N BasisCurves
// prims under one Xform (one 4-point curve each, with widths), the shape of files that cost the reader
// time quadratic in the prims before it concatenated them in one pass; reported as prims per second.
#include "kernel/io/curve_io.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

using namespace groom;

namespace {

const CurveSet& synthetic()
{
    static const CurveSet cs = [] {
        const size_t curves = 10000, per = 32;
        CurveSet s = CurveSet::from_counts(std::vector<int64_t>(curves, per));
        auto P = s.positions_for_write();
        auto w = s.add<float>(Domain::Point, attr::width);
        auto cd = s.add<float3>(Domain::Point, "Cd");
        auto id = s.add<int64_t>(Domain::Curve, attr::id);
        for (size_t c = 0; c < curves; ++c) {
            id[c] = static_cast<int64_t>(c * 2654435761u % 1000003);
            const float a = 0.000628f * c, r = 8.0f + 0.001f * (c % 97);
            for (size_t i = 0; i < per; ++i) {
                const size_t k = c * per + i;
                const float t = i / 31.0f;
                // Helical strands around a head-sized sphere: digits that do not round-trip short.
                P[k] = {r * std::cos(a) + 0.37f * t * std::sin(7 * t), 10.0f + 12.3456f * t, r * std::sin(a) + 0.37f * t * std::cos(5 * t)};
                w[k] = 0.008f * (1.0f - 0.9f * t);
                cd[k] = {0.2f + 0.3f * t, 0.1f, 0.05f};
            }
        }
        return s;
    }();
    return cs;
}

std::string path_for(const char* ext)
{
    return (std::filesystem::temp_directory_path() / ("groom_io_bench_" + std::to_string(::getpid()) + "." + ext)).string();
}

void write_bench(benchmark::State& state, const char* ext, PlyEncoding enc)
{
    const CurveSet& cs = synthetic();
    const std::string path = path_for(ext);
    CurveWriteOptions opt;
    opt.ply_encoding = enc;
    for (auto _ : state) write_curves(cs, path, opt);
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(cs.num_points()));
    state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(std::filesystem::file_size(path)));
    state.counters["MB"] = std::filesystem::file_size(path) / 1e6;
    std::filesystem::remove(path);
}

void read_bench(benchmark::State& state, const char* ext, PlyEncoding enc)
{
    const CurveSet& cs = synthetic();
    const std::string path = path_for(ext);
    CurveWriteOptions opt;
    opt.ply_encoding = enc;
    write_curves(cs, path, opt);
    for (auto _ : state) {
        CurveSet back = read_curves(path);
        benchmark::DoNotOptimize(back.positions().data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(cs.num_points()));
    state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(std::filesystem::file_size(path)));
    std::filesystem::remove(path);
}

void usda_prims_bench(benchmark::State& state)
{
    const auto n = static_cast<size_t>(state.range(0));
    const std::string path = path_for("usda");
    {
        std::string text = "#usda 1.0\ndef Xform \"groom\" {\n";
        for (size_t i = 0; i < n; ++i) {
            const std::string x = std::to_string(0.001 * static_cast<double>(i));
            text += "    def BasisCurves \"c" + std::to_string(i) + "\" {\n        uniform token type = \"linear\"\n        int[] curveVertexCounts = [4]\n"
                    "        point3f[] points = [(" + x + ", 0, 0), (" + x + ", 1, 0), (" + x + ", 2, 0), (" + x + ", 3, 0)]\n"
                    "        float[] widths = [0.01, 0.01, 0.01, 0.01] (interpolation = \"vertex\")\n    }\n";
        }
        text += "}\n";
        std::FILE* f = std::fopen(path.c_str(), "wb");
        std::fwrite(text.data(), 1, text.size(), f);
        std::fclose(f);
    }
    for (auto _ : state) {
        CurveSet back = read_curves(path);
        benchmark::DoNotOptimize(back.positions().data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(n));
    std::filesystem::remove(path);
}

}  // namespace

BENCHMARK(usda_prims_bench)->Name("read_usda_prims")->Arg(20000)->Arg(200000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(write_bench, usda, "usda", PlyEncoding::Binary)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_bench, usda, "usda", PlyEncoding::Binary)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_bench, ply_binary, "ply", PlyEncoding::Binary)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_bench, ply_binary, "ply", PlyEncoding::Binary)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_bench, ply_ascii, "ply", PlyEncoding::Ascii)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_bench, ply_ascii, "ply", PlyEncoding::Ascii)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_bench, hair, "hair", PlyEncoding::Binary)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_bench, hair, "hair", PlyEncoding::Binary)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_bench, obj, "obj", PlyEncoding::Binary)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_bench, obj, "obj", PlyEncoding::Binary)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
