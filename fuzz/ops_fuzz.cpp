// libFuzzer target for the ops (issue 20): every geometry command of `groom`, run in process through
// cli::run_captured on structured random input, so each op sees exactly what the command line gives
// it (option parsing, the decimal-integer check, each op's params validate(), the memory budget).
//
// From the fuzz bytes it builds
//   - guide / input curves: 0..8 curves of 0, 1, 2, a few or 200 points, with duplicate points,
//     points on, inside and far from the head, coordinates and widths of 1e30, 3e38, 1e-30, NaN,
//     inf (curves are validated as every reader does, so NaN/inf positions and widths are refused
//     at ingest: that refusal is a clean error);
//   - the scalp: the default head (16 bands) at three scales (cm, m, 1e4), or a small mesh from the
//     bytes (degenerate, tiny, huge and far-away triangles; the head plus one stray triangle),
//     converted with build_scalp under a 16 MiB budget, as `--scalp mesh` does (a quarter of the
//     time with its rims filled up to a fuzzed length, as `groom scalp --fill-holes`);
//   - 0..10 options of the command, each with a value drawn from the numbers its help text gives
//     (the documented range's ends, the default, and their float neighbours), from a pool of
//     extremes (0, -1, 1e-30, 1e30, 3e38, nan, inf, 2^31, 2^63 ...), from the words of its help
//     text (enum names), or lists and x,y,z vectors of those.
// The option names and their help come from `groom CMD --help`, so a new option is fuzzed without
// touching this file.
//
// Checked on every run: the exit code is 0, 1 or 2; a failure is a groom error (not "unexpected
// failure", the CLI's name for a std::exception that is not ours); every curve output is finite
// (a command that made NaN is refused when it writes, which would otherwise look like a clean error)
// and, as for every target, no crash, sanitizer report, hang or allocation above libFuzzer's limit.
// Work is bounded by --memory 0.0625 (64 MiB of output estimates) and --threads 1.
//
// GROOM_FUZZ_OP=<command> fuzzes one command (scripts/fuzz.sh runs target op_<command> that way,
// each with its own corpus); unset, the last byte picks the command (the provider reads integers
// from the end). GROOM_FUZZ_WRITE_SEEDS=DIR writes the checked-in seeds (fuzz/seeds/) and exits.
#include "cli/command.h"
#include "fields/scalp_field.h"
#include "kernel/curve_set.h"
#include "kernel/error.h"
#include "kernel/io/memory_files.h"
#include "ops/head.h"

#include <fuzzer/FuzzedDataProvider.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace groom;

namespace {

/// One option of a command, read from its --help line.
struct Option {
    std::string name;       ///< "--count"
    char kind = 'b';        ///< f float, i int, u unsigned, t text, b flag
    std::vector<std::string> choices;  ///< {a,b,c} of a CLI11 IsMember
    std::vector<std::string> words;    ///< identifier-like words of the help text (enum names)
    std::vector<double> numbers;       ///< numbers in the help text (range ends, default)
    bool required = false;
};

enum class InputKind { None, Curves, Puffs };

struct Command {
    std::string name;
    InputKind input = InputKind::Curves;
    bool scalp = false;
    std::string output = "mem:out";    ///< what -o names
    std::vector<Option> options;
    /// Values given unless the fuzzer sets the option (or one of `unless`) itself: defaults that
    /// cost more than a fuzz run may take (gather's 20000 hairs: 13 s on two cores), and required
    /// options with a value that works, so most runs reach the op. "@x,y,z" is scaled with the head.
    struct Light {
        std::string option, value;
        std::vector<std::string> unless = {};
    };
    std::vector<Light> light = {};
    /// Options whose valid values reach far beyond what a fuzz run may take: a value drawn above
    /// `most` but valid is given as `most` (values past the range's end are still given, to be
    /// refused). `groom head --resolution 1024` takes 51 s in a Release build on one thread (2 M
    /// quads, each vertex marched in from outside); sections' `--points 99999` on 30-unit guides 5 s.
    struct Costly {
        std::string option;
        double most = 0.0, valid_to = 0.0;
    };
    std::vector<Costly> costly = {};
};

/// The commands whose work is an op in ops/, and what they take.
std::vector<Command> commands = {
    {"resample", InputKind::Curves, false, "mem:out", {}, {{"--count", "8", {"--segment-length"}}}},
    {"project", InputKind::Curves, true},
    {"cull", InputKind::Curves, true},        {"hairline", InputKind::None, true},
    {"parting", InputKind::None, true},       {"cornrow-guides", InputKind::None, true},
    {"braid", InputKind::Curves, false},
    // The automatic density (a segment every 1/200 of the gap between guides) is thousands a side.
    {"partition", InputKind::Curves, true, "mem:out", {}, {{"--count", "8", {"--spacing"}}}},
    {"populate", InputKind::Curves, false},   {"curl", InputKind::Curves, false},
    {"generate", InputKind::Curves, true, "mem:out", {}, {{"--count", "50"}}},
    {"puff", InputKind::None, true, "mem:out", {},
     {{"--center", "@0,12,-1"}, {"--radius", "@3"}, {"--sphere-center", "@0,20,-1"}, {"--sphere-radius", "@5"}, {"--hairs", "20"}}},
    {"gather", InputKind::Puffs, true, "mem:out", {}, {{"--hairs", "200"}}},
    // The default 30-unit guides hang 30 m below a head in metres, where every query is exact (slow
    // far from the scalp: README "Not yet"), 10 s a run under ASan.
    {"sections", InputKind::None, true, "mem:out", {}, {{"--length", "@30"}}, {{"--points", 2000, 100000}}},
    {"edges", InputKind::None, true},
    {"render", InputKind::Curves, false, "out.png"},
    {"head", InputKind::None, false, "head.obj", {}, {}, {{"--resolution", 128, 1024}}},
};

/// Options the harness sets itself, or that only matter for a mesh read from a file.
const std::vector<std::string> kSkipped = {"--help", "--threads", "--quiet", "--verbose", "--force", "--memory", "--output",
                                           "--scalp", "--scalp-voxel", "--scalp-band", "--scalp-flip", "--adjacent"};
/// Options naming curve files the command reads / writes.
const std::vector<std::string> kCurveInputs = {"--hairline", "--parting"};
const std::vector<std::string> kCurveOutputs = {"--tails-out", "--guides-out", "--bands-out", "--partings-out", "--roots-out"};

bool contains(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

std::filesystem::path sandbox;
std::ostringstream discard;

std::vector<Option> parse_help(const std::string& help)
{
    std::vector<Option> out;
    std::istringstream in(help);
    std::string line;
    const std::regex head(R"(^  (?:-\w,)?(--[A-Za-z0-9-]+)(?: ([A-Z][A-Z:]*[^ ]*(?: \.\.\.)?))?(.*)$)");
    const std::regex number(R"(-?[0-9]+(?:\.[0-9]+)?(?:e[-+]?[0-9]+)?)");
    const std::regex word(R"([a-z][a-z0-9_]*(?::[A-Z0-9])?)");
    bool in_options = false;
    for (std::string description; std::getline(in, line);) {
        if (line.rfind("Options:", 0) == 0) in_options = true;
        if (!in_options) continue;
        std::smatch m;
        Option* cur = out.empty() ? nullptr : &out.back();
        if (std::regex_match(line, m, head)) {
            Option o;
            o.name = m[1];
            const std::string type = m[2];
            if (type.empty()) o.kind = 'b';
            else if (type.rfind("FLOAT", 0) == 0) o.kind = 'f';
            else if (type.rfind("UINT", 0) == 0) o.kind = 'u';
            else if (type.rfind("INT", 0) == 0) o.kind = 'i';
            else o.kind = 't';
            const auto open = type.find('{'), close = type.find('}');
            if (open != std::string::npos && close != std::string::npos) {
                std::stringstream ss(type.substr(open + 1, close - open - 1));
                for (std::string c; std::getline(ss, c, ',');) o.choices.push_back(c);
            }
            o.required = std::string(m[3]).rfind(" REQUIRED", 0) == 0;
            out.push_back(o);
            cur = &out.back();
            description = type + " " + std::string(m[3]);
        }
        else if (cur && line.rfind("      ", 0) == 0) {
            description = line;
        }
        else {
            continue;
        }
        for (auto it = std::sregex_iterator(description.begin(), description.end(), number); it != std::sregex_iterator(); ++it)
            cur->numbers.push_back(std::strtod(it->str().c_str(), nullptr));
        for (auto it = std::sregex_iterator(description.begin(), description.end(), word); it != std::sregex_iterator(); ++it)
            if (it->str().size() <= 12) cur->words.push_back(it->str());
    }
    return out;
}

std::string help_of(const std::string& command)
{
    std::ostringstream captured;
    std::streambuf* old = std::cout.rdbuf(captured.rdbuf());
    std::string error;
    groom::cli::run_captured({command, "--help"}, error);
    std::cout.rdbuf(old);
    return captured.str();
}

// --- scalps --------------------------------------------------------------------------------------

const float kHeadScales[] = {1.0f, 0.01f, 1e4f};
// 16 MiB: the conversion is most of a run's time, and under ASan and coverage its cost follows the
// grid's size. At 64 MiB a fuzzed head with a stray triangle far away (`hairline` on it) took 3.3 s
// to convert, twice in one input (libFuzzer runs an input again when it left memory allocated, to
// look for a leak), 11.5 s with the other core busy: on CI's slower cores, past the 30 s timeout
// the fuzz stage then had. A grid that would exceed the budget is refused, itself a path to fuzz.
constexpr uint64_t kScalpBudget = 16ull << 20;

ScalpBuildParams scalp_params()
{
    ScalpBuildParams p;
    p.memory_budget = kScalpBudget;
    p.source = "fuzz scalp";
    return p;
}

PolygonSoup small_head(float scale)
{
    HeadParams hp;
    hp.resolution = 16;
    hp.scale = scale;
    return make_head(hp);
}

// --- values --------------------------------------------------------------------------------------

const double kFloatPool[] = {0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 3.0, 0.25, 1e-30, 1e-6, 1e-3, 0.01, 0.1, 8.0, 10.0, 64.0,
                             100.0, 256.0, 1000.0, 1e6, 1e15, 1e20, 1e30, 3e38, -1e30, -3e38, 0.999999, 89.999, 90.0,
                             179.999, 180.0, 360.0, 720.0,
                             std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()};
const char* const kIntPool[] = {"0", "1", "2", "3", "4", "5", "-1", "7", "16", "64", "255", "256", "257", "1000", "4096",
                                "100000", "1000000", "2147483647", "2147483648", "4294967296", "9223372036854775807",
                                "-2147483648", "18446744073709551615", "010", "1e3", ""};

std::string format_double(double v)
{
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

double pick_number(FuzzedDataProvider& fdp, const Option& o)
{
    const int how = fdp.ConsumeIntegralInRange(0, 9);
    if (how < 6 && !o.numbers.empty()) {
        double v = o.numbers[fdp.ConsumeIntegralInRange<size_t>(0, o.numbers.size() - 1)];
        switch (fdp.ConsumeIntegralInRange(0, 9)) {
        case 1: v = std::nextafter(float(v), 1e30f); break;   // just past a range's end
        case 2: v = std::nextafter(float(v), -1e30f); break;
        case 3: v = v * 10.0; break;
        default: break;
        }
        return v;
    }
    if (how < 9) return kFloatPool[fdp.ConsumeIntegralInRange<size_t>(0, std::size(kFloatPool) - 1)];
    return fdp.ConsumeFloatingPoint<float>();
}

std::string number_list(FuzzedDataProvider& fdp, const Option& o, int n)
{
    std::string s;
    for (int i = 0; i < n; ++i) s += (i ? "," : "") + format_double(pick_number(fdp, o));
    return s;
}

/// x,y,z of a point near the default head of `scale` (on, above or inside its cranium).
std::string head_point(FuzzedDataProvider& fdp, float scale)
{
    const float3 dir = normalize(float3(fdp.ConsumeFloatingPointInRange(-1.0f, 1.0f), fdp.ConsumeFloatingPointInRange(-0.3f, 1.0f),
                                        fdp.ConsumeFloatingPointInRange(-1.0f, 1.0f)),
                                 float3(0, 1, 0));
    const float3 p = (float3(0, 3, -1) + dir * fdp.ConsumeFloatingPointInRange(0.0f, 20.0f)) * scale;
    return format_double(p.x) + "," + format_double(p.y) + "," + format_double(p.z);
}

std::string pick_value(FuzzedDataProvider& fdp, const Option& o, float scale)
{
    if (o.name == "--through") {  // X,Y,Z/X,Y,Z/...
        std::string s = head_point(fdp, scale);
        for (int n = fdp.ConsumeIntegralInRange(0, 4); n > 0; --n) s += "/" + (fdp.ConsumeBool() ? head_point(fdp, scale) : s);
        return s;
    }
    switch (o.kind) {
    case 'f': return format_double(pick_number(fdp, o));
    case 'i':
    case 'u': {
        const int how = fdp.ConsumeIntegralInRange(0, 3);
        if (how == 0 && !o.numbers.empty()) {
            const double v = o.numbers[fdp.ConsumeIntegralInRange<size_t>(0, o.numbers.size() - 1)];
            return std::to_string(static_cast<long long>(std::clamp(v, -1e18, 1e18)) + fdp.ConsumeIntegralInRange(-1, 1));
        }
        if (how == 1) return std::to_string(fdp.ConsumeIntegralInRange(-2, 300));
        return kIntPool[fdp.ConsumeIntegralInRange<size_t>(0, std::size(kIntPool) - 1)];
    }
    default: break;
    }
    // Text: an enum value, a word of the help text, a list of numbers (x,y,z; lo,hi; a spline), or bytes.
    switch (fdp.ConsumeIntegralInRange(0, 8)) {
    case 7:
    case 8: return head_point(fdp, scale);
    case 0:
        if (!o.choices.empty()) return o.choices[fdp.ConsumeIntegralInRange<size_t>(0, o.choices.size() - 1)];
        [[fallthrough]];
    case 1:
        if (!o.words.empty()) {
            std::string w = o.words[fdp.ConsumeIntegralInRange<size_t>(0, o.words.size() - 1)];
            if (w.size() > 2 && w[w.size() - 2] == ':') w = w.substr(0, w.size() - 1) + std::to_string(fdp.ConsumeIntegralInRange(-1, 9));
            return w;
        }
        [[fallthrough]];
    case 2: return number_list(fdp, o, 3);
    case 3: return number_list(fdp, o, 2);
    case 4: return number_list(fdp, o, fdp.ConsumeIntegralInRange(1, 6));
    case 5: return number_list(fdp, o, 4);
    default: return fdp.ConsumeRandomLengthString(24);
    }
}

// --- geometry ------------------------------------------------------------------------------------

/// A coordinate: mostly ordinary (a head of `scale`), sometimes an extreme.
float coordinate(FuzzedDataProvider& fdp, float scale)
{
    static const float specials[] = {0.0f, 1e30f, -1e30f, 3e38f, 1e-30f, 1e20f, 16777217.0f, std::numeric_limits<float>::quiet_NaN(),
                                     std::numeric_limits<float>::infinity()};
    if (fdp.ConsumeIntegralInRange(0, 15) == 0) return specials[fdp.ConsumeIntegralInRange<size_t>(0, std::size(specials) - 1)];
    return fdp.ConsumeFloatingPointInRange(-15.0f, 15.0f) * scale;
}

/// Curves around (and in, and far from) the default head of `scale`: each starts near the scalp
/// (the cranium, a sphere of about 9 cm round (0, 3, -1)) and walks outward, or is made of
/// duplicates, or of arbitrary points.
CurveSet make_curves(FuzzedDataProvider& fdp, float scale, int max_curves)
{
    static const int64_t kCounts[] = {0, 1, 2, 2, 3, 4, 5, 8, 16, 24, 200};
    const int n = fdp.ConsumeIntegralInRange(0, max_curves);
    std::vector<int64_t> counts(n);
    for (auto& c : counts) c = kCounts[fdp.ConsumeIntegralInRange<size_t>(0, std::size(kCounts) - 1)];
    CurveSet cs = CurveSet::from_counts(std::span<const int64_t>(counts));
    auto P = cs.positions_for_write();
    const auto off = cs.offsets();
    for (int c = 0; c < n; ++c) {
        const int mode = fdp.ConsumeIntegralInRange(0, 5);
        float3 dir = normalize(float3(fdp.ConsumeFloatingPointInRange(-1.0f, 1.0f), fdp.ConsumeFloatingPointInRange(-0.2f, 1.0f),
                                      fdp.ConsumeFloatingPointInRange(-1.0f, 1.0f)),
                               float3(0, 1, 0));
        float3 p = (float3(0, 3, -1) + dir * fdp.ConsumeFloatingPointInRange(7.0f, 11.0f)) * scale;
        const float step = (mode == 4 ? fdp.ConsumeFloatingPointInRange(0.0f, 1e-5f) : fdp.ConsumeFloatingPointInRange(0.05f, 2.0f)) * scale;
        for (int64_t i = off[c]; i < off[c + 1]; ++i) {
            if (mode == 0) p = {coordinate(fdp, scale), coordinate(fdp, scale), coordinate(fdp, scale)};
            else if (mode == 1 && i > off[c] && fdp.ConsumeBool()) { /* duplicate of the previous point */ }
            else if (mode == 5 && fdp.ConsumeIntegralInRange(0, 7) == 0) p = p + float3(coordinate(fdp, scale), 0, 0);
            else p = p + (dir + float3(fdp.ConsumeFloatingPointInRange(-0.5f, 0.5f), fdp.ConsumeFloatingPointInRange(-0.5f, 0.5f),
                                        fdp.ConsumeFloatingPointInRange(-0.5f, 0.5f))) * step;
            P[i] = p;
        }
    }
    if (fdp.ConsumeBool()) {
        // The last two are refused when read; the rest (0, 1e30, 3e38 included) reach the op.
        static const float widths[] = {0.0f, 0.01f, 0.05f, 1.0f, 1e30f, 3e38f, 1e-30f, -1.0f, std::numeric_limits<float>::quiet_NaN()};
        auto w = cs.add<float>(Domain::Point, "width");
        const float common = widths[fdp.ConsumeIntegralInRange<size_t>(0, std::size(widths) - 3)];
        for (auto& x : w) x = fdp.ConsumeIntegralInRange(0, 31) == 0 ? widths[fdp.ConsumeIntegralInRange<size_t>(0, std::size(widths) - 1)] : common * scale;
    }
    if (fdp.ConsumeBool()) {
        auto id = cs.add<int64_t>(Domain::Curve, "id");
        for (auto& x : id) x = fdp.ConsumeBool() ? fdp.ConsumeIntegral<int64_t>() : int64_t(&x - id.data());
    }
    return cs;
}

/// A small mesh: arbitrary triangles (degenerate, repeated, tiny, huge) or the head with a stray
/// triangle far away (the automatic voxel then comes out coarse).
PolygonSoup make_mesh(FuzzedDataProvider& fdp)
{
    if (fdp.ConsumeBool()) {
        HeadParams hp;
        hp.resolution = 8;
        PolygonSoup s = make_head(hp);
        const float far = std::pow(10.0f, float(fdp.ConsumeIntegralInRange(1, 38)));
        const int32_t base = int32_t(s.points.size());
        s.points.push_back({far, 0, 0});
        s.points.push_back({far, 1, 0});
        s.points.push_back({far, 0, fdp.ConsumeBool() ? 1.0f : 0.0f});
        const int32_t tri[] = {base, base + 1, base + 2};
        s.add_face(tri);
        return s;
    }
    PolygonSoup s;
    const float scale = std::pow(10.0f, float(fdp.ConsumeIntegralInRange(-30, 30)));
    const int nv = fdp.ConsumeIntegralInRange(3, 24);
    for (int i = 0; i < nv; ++i) {
        if (i > 0 && fdp.ConsumeIntegralInRange(0, 5) == 0) s.points.push_back(s.points[fdp.ConsumeIntegralInRange(0, i - 1)]);
        else s.points.push_back(float3(coordinate(fdp, 1.0f), coordinate(fdp, 1.0f), coordinate(fdp, 1.0f)) * scale);
    }
    const int nf = fdp.ConsumeIntegralInRange(1, 32);
    for (int f = 0; f < nf; ++f) {
        const int k = fdp.ConsumeIntegralInRange(0, 5) == 0 ? 4 : 3;
        std::vector<int32_t> idx(k);
        for (auto& i : idx) i = fdp.ConsumeIntegralInRange(0, nv - 1);
        s.add_face(idx);
    }
    return s;
}

std::vector<std::string> scratch;  ///< mem: paths to erase after each run

bool print_runs = false;

std::string store_curves(const std::string& name, CurveSet cs)
{
    if (print_runs) {
        std::string line = "ops_fuzz: " + name + ":";
        for (size_t c = 0; c < cs.num_curves(); ++c) {
            line += " [";
            for (const float3& p : cs.positions().subspan(cs.offsets()[c], cs.points_in(c)))
                line += "(" + format_double(p.x) + "," + format_double(p.y) + "," + format_double(p.z) + ")";
            line += "]";
        }
        std::fprintf(stderr, "%s\n", line.c_str());
    }
    const std::string path = "mem:fuzz_" + name;
    store_memory_curves(path, std::move(cs));
    scratch.push_back(path);
    return path;
}

/// A finite copy of everything a command wrote; traps on NaN or inf positions or widths.
void check_output(const std::string& path)
{
    CurveSet out;
    try {
        out = take_memory_curves(path);
    }
    catch (const Error&) {
        return;  // not written (the option was not given, or the command failed)
    }
    for (const float3& p : out.positions())
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) __builtin_trap();
    const auto w = out.find<float>(Domain::Point, "width");
    for (float x : w)
        if (!(std::isfinite(x) && x >= 0.0f)) __builtin_trap();
}

/// Head `i` (and a hairline on it) as "mem:fuzz_head<i>", built at its first use and kept:
/// converting a mesh is the slow part of a run, and commands without a scalp need none.
void ensure_head(int i)
{
    static bool built[std::size(kHeadScales)] = {};
    if (built[i]) return;
    built[i] = true;
    // A coarse voxel (the head is about 40 cm across: 64 voxels) keeps the build near a second under
    // ASan; the fuzzed meshes use the automatic one.
    ScalpBuildParams p = scalp_params();
    p.voxel_size = 0.6f * kHeadScales[i];
    auto field = std::make_shared<const ScalpField>(build_scalp(small_head(kHeadScales[i]), p));
    const std::string name = "mem:fuzz_head" + std::to_string(i);
    store_memory_scalp(name, field);
    std::string error;
    const int code = groom::cli::run_captured({"hairline", "--scalp", name, "-o", name + "_hairline", "--quiet"}, error);
    if (code != 0) {
        std::fprintf(stderr, "ops_fuzz: hairline on head %d failed: %s\n", i, error.c_str());
        std::abort();
    }
}

const Command* only = nullptr;
// GROOM_FUZZ_PRINT=1 (print_runs, above): print each command line, its inputs and its result.
/// Exit codes seen (0, 1, 2) and inputs refused before the command ran, printed at exit with
/// GROOM_FUZZ_PRINT, to check the fuzzer reaches the ops rather than only their refusals.
int64_t seen[4] = {};

/// Option names of the last run (for write_seeds).
std::vector<std::string> last_options;
int run_one(const uint8_t* data, size_t size, const Command* forced);
void write_seeds(const std::filesystem::path& dir);

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    sandbox = std::filesystem::temp_directory_path() / ("groom_ops_fuzz_" + std::to_string(::getpid()));
    std::filesystem::remove_all(sandbox);
    std::filesystem::create_directories(sandbox);
    std::filesystem::current_path(sandbox);  // render and head write real files: here, removed after each run
    std::atexit([] {
        std::error_code ec;
        std::filesystem::remove_all(sandbox, ec);
    });
    for (Command& c : commands) {
        for (Option& o : parse_help(help_of(c.name)))
            if (!contains(kSkipped, o.name)) c.options.push_back(o);
        if (c.options.empty()) {
            std::cerr << "ops_fuzz: no options read from `groom " << c.name << " --help`\n";
            std::abort();
        }
    }
    if (const char* op = std::getenv("GROOM_FUZZ_OP")) {
        for (const Command& c : commands)
            if (c.name == op) only = &c;
        if (!only) {
            std::cerr << "ops_fuzz: GROOM_FUZZ_OP=" << op << " is not a fuzzed command\n";
            std::abort();
        }
    }
    print_runs = std::getenv("GROOM_FUZZ_PRINT") != nullptr;
    if (print_runs)
        std::atexit([] { std::fprintf(stderr, "ops_fuzz: exit 0: %lld, 1: %lld, 2: %lld; inputs refused: %lld\n", (long long)seen[0], (long long)seen[1], (long long)seen[2], (long long)seen[3]); });
    std::cout.rdbuf(discard.rdbuf());
    std::cerr.rdbuf(discard.rdbuf());
    if (const char* dir = std::getenv("GROOM_FUZZ_WRITE_SEEDS")) {
        write_seeds(dir);
        std::exit(0);
    }
    return 0;
}

namespace {

/// One fuzz input: the exit code of the command it ran, or -1 when its input was refused before.
int run_one(const uint8_t* data, size_t size, const Command* forced)
{
    FuzzedDataProvider fdp(data, size);
    const Command& cmd = forced ? *forced : commands[fdp.ConsumeIntegralInRange<size_t>(0, commands.size() - 1)];
    const int head = fdp.ConsumeIntegralInRange(0, int(std::size(kHeadScales)));  // == size: a mesh from the bytes
    const float scale = head < int(std::size(kHeadScales)) ? kHeadScales[head] : 1.0f;

    std::vector<std::string> args{cmd.name, "--threads", "1", "--quiet", "--memory", "0.0625"};
    std::vector<std::string> outputs;
    if (cmd.output.rfind("mem:", 0) == 0) outputs.push_back(cmd.output);
    args.insert(args.end(), {"-o", cmd.output});
    scratch.clear();

    // Inputs, each validated as a reader validates what it read: invalid ones are refused there.
    auto curves = [&](const std::string& name, int max_curves) -> std::string {
        CurveSet cs = make_curves(fdp, scale, max_curves);
        try {
            cs.validate(name);
        }
        catch (const Error&) {
            return {};
        }
        return store_curves(name, std::move(cs));
    };
    bool refused = false;
    if (cmd.input == InputKind::Curves) {
        const std::string in = curves("in", 8);
        refused |= in.empty();
        args.push_back(in);
    }
    if (cmd.scalp) {
        std::string scalp = "mem:fuzz_head" + std::to_string(head);
        if (head < int(std::size(kHeadScales))) ensure_head(head);
        if (head == int(std::size(kHeadScales))) {
            const PolygonSoup mesh = make_mesh(fdp);
            ScalpBuildParams p = scalp_params();
            const int voxel = fdp.ConsumeIntegralInRange(0, 3);
            if (voxel > 0) p.voxel_size = float(pick_number(fdp, Option{}));
            p.band_voxels = voxel == 3 ? 1.0f : 3.0f;
            // Holes filled (`groom scalp --fill-holes`) on a hostile mesh's rims: pinches, repeated
            // points and collinear runs reach CGAL's hole triangulation.
            if (fdp.ConsumeIntegralInRange(0, 3) == 0) p.fill_holes = float(pick_number(fdp, Option{}));
            try {
                store_memory_scalp("mem:fuzz_mesh", std::make_shared<const ScalpField>(build_scalp(mesh, p)));
                scalp = "mem:fuzz_mesh";
            }
            catch (const Error&) {
                refused = true;  // the mesh (or its voxel) was refused as `--scalp mesh` refuses it
            }
            catch (const std::exception& e) {
                std::fprintf(stderr, "ops_fuzz: build_scalp threw a std::exception that is not a groom error: %s\n", e.what());
                __builtin_trap();
            }
        }
        args.insert(args.end(), {"--scalp", scalp});
    }
    if (cmd.input == InputKind::Puffs) {
        // gather's inputs are puffs: one from `groom puff` on this head, or arbitrary curves.
        if (fdp.ConsumeBool() && !refused) {
            std::string error;
            const std::string puff = store_curves("puff", CurveSet());
            const float3 c = float3(0, 12, -1) * scale;
            groom::cli::run_captured({"puff", "--scalp", args.back(), "-o", puff, "--threads", "1", "--quiet", "--center",
                                      format_double(c.x) + "," + format_double(c.y) + "," + format_double(c.z), "--radius",
                                      format_double(3 * scale), "--sphere-center",
                                      format_double(c.x) + "," + format_double(c.y + 8 * scale) + "," + format_double(c.z),
                                      "--sphere-radius", format_double(5 * scale), "--rows", "3", "--cols", "3"},
                                     error);
            args.push_back(puff);
        }
        else {
            const std::string in = curves("puffs", 4);
            refused |= in.empty();
            args.push_back(in);
        }
    }

    // The required options (each time), then up to ten drawn from all.
    std::vector<const Option*> chosen;
    for (const Option& o : cmd.options) {
        const bool has_light = std::any_of(cmd.light.begin(), cmd.light.end(), [&](const Command::Light& l) { return l.option == o.name; });
        if (o.required && (!has_light || fdp.ConsumeIntegralInRange(0, 3) == 0)) chosen.push_back(&o);
    }
    for (int k = fdp.ConsumeIntegralInRange(0, 3) == 0 ? fdp.ConsumeIntegralInRange(0, 10) : fdp.ConsumeIntegralInRange(0, 3); k > 0; --k)
        chosen.push_back(&cmd.options[fdp.ConsumeIntegralInRange<size_t>(0, cmd.options.size() - 1)]);
    for (const Command::Light& l : cmd.light) {
        const bool set = std::any_of(chosen.begin(), chosen.end(), [&](const Option* o) { return o->name == l.option || contains(l.unless, o->name); });
        if (set) continue;
        std::string value = l.value;
        if (value[0] == '@') {
            std::stringstream ss(value.substr(1));
            value.clear();
            for (std::string x; std::getline(ss, x, ',');) value += (value.empty() ? "" : ",") + format_double(std::stof(x) * scale);
        }
        args.insert(args.end(), {l.option, value});
    }
    last_options.clear();
    for (const Option* o : chosen) last_options.push_back(o->name);
    for (const Option* option : chosen) {
        const Option& o = *option;
        args.push_back(o.name);
        if (o.kind == 'b') continue;
        if (contains(kCurveInputs, o.name)) {
            if (o.name == "--hairline" && fdp.ConsumeBool() && head < int(std::size(kHeadScales)))
                args.push_back("mem:fuzz_head" + std::to_string(head) + "_hairline");
            else {
                args.push_back(curves(o.name.substr(2), 3));
                refused |= args.back().empty();
            }
        }
        else if (contains(kCurveOutputs, o.name)) {
            args.push_back("mem:fuzz_out_" + o.name.substr(2));
            outputs.push_back(args.back());
        }
        else if (o.name == "--write-adjacent") args.push_back("adjacent.txt");
        else {
            std::string value = pick_value(fdp, o, scale);
            for (const Command::Costly& c : cmd.costly) {
                if (c.option != o.name) continue;
                // Plain decimal digits only: "1e3" and "010" stay, to be refused or read as given.
                const bool digits = !value.empty() && value.size() < 10 && std::all_of(value.begin(), value.end(), [](unsigned char ch) { return std::isdigit(ch) != 0; });
                const double v = digits ? std::stod(value) : 0.0;
                if (digits && v > c.most && v <= c.valid_to) value = std::to_string(int64_t(c.most));
            }
            args.push_back(value);
        }
    }
    auto clean_up = [] {
        for (const std::string& p : scratch) erase_memory_curves(p);
        erase_memory_scalp("mem:fuzz_mesh");
        for (const auto& entry : std::filesystem::directory_iterator(sandbox)) std::filesystem::remove_all(entry.path());
    };
    if (print_runs) {
        std::string line = "groom";
        for (const std::string& a : args) line += " '" + a + "'";
        std::fprintf(stderr, "ops_fuzz: %s%s\n", line.c_str(), refused ? "  (input refused)" : "");
    }
    if (refused) {
        ++seen[3];
        clean_up();
        return -1;
    }

    std::string error;
    const int code = groom::cli::run_captured(args, error);
    if (code != 0 && code != 1 && code != 2) __builtin_trap();
    ++seen[code];
    if (print_runs) std::fprintf(stderr, "ops_fuzz: exit %d %s\n", code, error.c_str());
    // A std::exception that is not a groom::Error (std::out_of_range, std::length_error ...).
    if (code != 0 && error.rfind("unexpected failure", 0) == 0) {
        std::fprintf(stderr, "ops_fuzz: %s\n", error.c_str());
        __builtin_trap();
    }
    // NaN made by the op is refused when written: that is the op's bug, not a clean refusal.
    if (code != 0 && error.find("writing mem:") != std::string::npos) {
        std::fprintf(stderr, "ops_fuzz: %s\n", error.c_str());
        __builtin_trap();
    }
    for (const std::string& o : outputs) check_output(o);
    clean_up();
    return code;
}

/// GROOM_FUZZ_WRITE_SEEDS=DIR (`scripts/fuzz.sh --write-op-seeds`): writes the op targets' seed
/// corpus instead of fuzzing, so short runs (CI's 40 s) start from inputs that reach each op rather
/// than from libFuzzer's first inputs of a few bytes, which leave nearly every choice at its
/// default. Per command (or GROOM_FUZZ_OP's), byte strings from a fixed random stream of its own are
/// run as fuzz inputs; one is kept when its command exits 0 and it is the first to, or it sets an
/// option no kept seed set, up to kSeeds per command or kSeconds of tries. Written as
/// DIR/op_<command>/<n> and, with the byte that picks the command appended (the provider reads
/// integers from the end, the command's first), DIR/ops/<command>-<n>. The bytes mean what this
/// harness makes of them: regenerate after changing how it reads them.
void write_seeds(const std::filesystem::path& dir)
{
    constexpr int kSeeds = 6;
    constexpr double kSeconds = 30.0;
    constexpr size_t kBytes = 256;
    for (size_t ci = 0; ci < commands.size(); ++ci) {
        const Command& c = commands[ci];
        if (only && &c != only) continue;
        std::mt19937_64 random(20 + ci);  // per command: its candidates do not depend on the others' time
        std::filesystem::create_directories(dir / ("op_" + c.name));
        std::filesystem::create_directories(dir / "ops");
        std::set<std::string> covered;
        int kept = 0, tried = 0;
        const auto start = std::chrono::steady_clock::now();
        while (kept < kSeeds && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < kSeconds) {
            std::vector<uint8_t> bytes(kBytes);
            for (uint8_t& b : bytes) b = uint8_t(random() >> 56);
            ++tried;
            if (run_one(bytes.data(), bytes.size(), &c) != 0) continue;
            bool adds = kept == 0;
            for (const std::string& o : last_options) adds |= covered.insert(o).second;
            if (!adds) continue;
            const std::string name = std::to_string(kept);
            std::ofstream(dir / ("op_" + c.name) / name, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
            bytes.push_back(uint8_t(ci));
            std::ofstream(dir / "ops" / (c.name + "-" + name), std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
            ++kept;
        }
        std::fprintf(stderr, "ops_fuzz: %-15s %d seeds from %d tries (%zu options covered)\n", c.name.c_str(), kept, tried, covered.size());
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    run_one(data, size, only);
    return 0;
}
