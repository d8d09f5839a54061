#include "ops/curl.h"

#include "fields/keep_outside.h"
#include "kernel/curve_blocks.h"
#include "kernel/error.h"
#include "kernel/math/frames.h"
#include "kernel/math/polyline.h"
#include "kernel/math/spline.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"
#include "ops/hair_types.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <sstream>

namespace groom {

namespace {

// Rng streams (kernel/rng.h): one per purpose so adding a draw never shifts another.
constexpr uint64_t kStreamCurve = 0x6375726c01;   // per curve: frequency, phase
constexpr uint64_t kStreamShape = 0x6375726c02;   // per cycle: shape pick
constexpr uint64_t kStreamAmp = 0x6375726c03;     // per cycle: amplitude
constexpr uint64_t kStreamOffset = 0x6375726c04;  // per cycle: offset radius and direction

constexpr int64_t kMaxPoints = int64_t(1) << 31;

std::string num(double v) { return format_number(v); }

std::string range_text(const FloatRange& r) { return num(r.lo) + "," + num(r.hi); }

bool finite(const FloatRange& r) { return std::isfinite(r.lo) && std::isfinite(r.hi); }

const HairTypePreset& preset_of(const CurlParams& p)
{
    const HairTypePreset* preset = find_hair_type(p.hair_type);
    if (!preset) throw InvalidParam("curl: `type` must be one of " + hair_type_list() + " (got '" + p.hair_type + "')");
    return *preset;
}

float smoothstep(float x)
{
    x = std::clamp(x, 0.0f, 1.0f);
    return x * x * (3.0f - 2.0f * x);
}

/// One cycle's cross-section: centre + amplitude * R(phase) * shape(t).
struct Cycle {
    int shape = kCircle;
    float amplitude = 0.0f;
    float ox = 0.0f, oy = 0.0f;
};

/// Per-curve draws that fix its output size (computed in the count pass, reused in the fill).
struct CurveSetup {
    float frequency = 0.0f;
    int64_t points = 0;
};

struct Resolved {
    const HairTypePreset* preset = nullptr;
    CurlShapeTiers tiers;
    FloatRange amplitude;
    float amplitude_mid = 0.0f;
    ShapeTable table;
};

/// The cycle that cycle coordinate u falls in, of `count`: floor(u) clamped to [0, count - 1] in
/// double before converting (NaN gives 0). Converting first was undefined past int64's range, which
/// `--root-ease 1e30` reaches (u = -frequency x 1e30; UBSan stopped op_curl there while the op
/// seeds were written).
int64_t cycle_of(double u, int64_t count)
{
    const double f = std::floor(u);
    return f > 0.0 ? int64_t(std::min(f, double(std::max<int64_t>(count - 1, 0)))) : 0;
}

/// Root envelope: 0 on the straight part (u <= 0), a smoothstep up to 1 over `ramp` cycles.
float root_envelope(double u, float ramp)
{
    if (u < 0.0) return 0.0f;
    // Past the ramp the smoothstep is exactly 1 (u / ramp >= 1 when u >= ramp): no division there.
    if (ramp <= 0.0f || u >= double(ramp)) return 1.0f;
    return smoothstep(float(u / double(ramp)));
}

/// A curve's centreline: points evenly spaced (ds apart) in arc length with rotation-minimising
/// frames, what the curl winds around.
struct Centreline {
    std::vector<float3> points;
    std::vector<Frame> frames;
    double length = 0.0;
    double ds = 0.0;
    // Scratch kept from curve to curve by a worker (the spline, its lengths, the tangents).
    std::vector<float3> spline, tangents;
    std::vector<double> cumulative;

    /// Where arc length s falls on the grid: between points j and j1, fraction f.
    void spot(double s, int64_t& j, int64_t& j1, float& f) const
    {
        const int64_t last = int64_t(points.size()) - 1;
        const double x = ds > 0.0 ? s / ds : 0.0;
        j = std::clamp<int64_t>(int64_t(std::floor(x)), 0, std::max<int64_t>(last - 1, 0));
        f = last > 0 ? float(std::clamp(x - double(j), 0.0, 1.0)) : 0.0f;
        j1 = std::min(j + 1, last);
    }

    /// The centre at arc length s (a curled point's anchor: the place it curls around).
    float3 point_at(double s) const
    {
        int64_t j = 0, j1 = 0;
        float f = 0.0f;
        spot(s, j, j1, f);
        return lerp(points[size_t(j)], points[size_t(j1)], f);
    }

    /// Centres and frames (normal, binormal) at the arc lengths `s`, interpolated between grid points,
    /// into `at`: 9 floats a point (centre, normal, binormal). Each is
    ///     c = lerp of the grid's centres, t = renormalize(lerp of the tangents),
    ///     n = renormalize(lerp of the normals less their part along t), b = t x n
    /// (neighbouring frames differ by a small turn, so the blends are within 1e-3 of unit length and
    /// renormalize needs no square root; the frames of a sharp bend take the exact path). The points
    /// are interpolated by a loop without a branch, which GCC runs four at a time, and the few that
    /// need the exact path are done again one at a time: the same operations on each value as one
    /// point at a time, so the same bits. One at a time, pass 2 of curl_curve was a third of
    /// curling Sintel's hair (rdtsc), and this part of it about a third of that.
    void frames_at(std::span<const double> s, std::vector<int32_t>& lo, std::vector<int32_t>& hi, std::vector<float>& frac,
                   std::vector<float>& at, std::vector<uint8_t>& far) const
    {
        const size_t m = s.size();
        lo.resize(m);
        hi.resize(m);
        frac.resize(m);
        at.resize(9 * m);
        for (size_t k = 0; k < m; ++k) {
            int64_t j = 0, j1 = 0;
            spot(s[k], j, j1, frac[k]);
            lo[k] = int32_t(j), hi[k] = int32_t(j1);
        }
        far.resize(m);
        interpolate(m, points.data(), frames.data(), lo.data(), hi.data(), frac.data(), at.data(), far.data());
        // The rare blend that is not within 1e-3 of unit length (a sharp bend) takes renormalize's
        // exact path: the point again, one at a time.
        for (size_t k = 0; k < m; ++k) {
            if (!far[k]) continue;
            const int32_t j = lo[k], j1 = hi[k];
            const float f = frac[k];
            const float3 t = renormalize(lerp(frames[size_t(j)].t, frames[size_t(j1)].t, f), frames[size_t(j)].t);
            float3 n = lerp(frames[size_t(j)].n, frames[size_t(j1)].n, f);
            n = renormalize(n - t * dot(n, t), frames[size_t(j)].n);
            const float3 b = cross(t, n);
            float* q = at.data() + 9 * k;
            q[3] = n.x, q[4] = n.y, q[5] = n.z, q[6] = b.x, q[7] = b.y, q[8] = b.z;
        }
    }

private:
    /// frames_at's loop, renormalize's path without a square root for every point (far[k] = 1 where
    /// a blend's squared length is not within 1e-3 of 1 and that path does not apply). The arguments
    /// are restrict-qualified parameters (GCC does not vectorise it with restrict locals), and it
    /// copies the points and frames (nor with references to them).
    static void interpolate(size_t m, const float3* __restrict P, const Frame* __restrict F, const int32_t* __restrict lo,
                            const int32_t* __restrict hi, const float* __restrict frac, float* __restrict out, uint8_t* __restrict far)
    {
        for (size_t k = 0; k < m; ++k) {
            const float f = frac[k];
            const float3 p0 = P[lo[k]], p1 = P[hi[k]], t0 = F[lo[k]].t, t1 = F[hi[k]].t, n0 = F[lo[k]].n, n1 = F[hi[k]].n;
            float tx = t0.x + (t1.x - t0.x) * f, ty = t0.y + (t1.y - t0.y) * f, tz = t0.z + (t1.z - t0.z) * f;
            const float tl2 = tx * tx + ty * ty + tz * tz, tg = 1.5f - 0.5f * tl2;
            tx = tx * tg, ty = ty * tg, tz = tz * tg;
            float nx = n0.x + (n1.x - n0.x) * f, ny = n0.y + (n1.y - n0.y) * f, nz = n0.z + (n1.z - n0.z) * f;
            const float d = nx * tx + ny * ty + nz * tz;
            nx = nx - tx * d, ny = ny - ty * d, nz = nz - tz * d;
            const float nl2 = nx * nx + ny * ny + nz * nz, ng = 1.5f - 0.5f * nl2;
            nx = nx * ng, ny = ny * ng, nz = nz * ng;
            far[k] = uint8_t(!((tl2 > 0.999f) & (tl2 < 1.001f) & (nl2 > 0.999f) & (nl2 < 1.001f)));
            float* q = out + 9 * k;
            q[0] = p0.x + (p1.x - p0.x) * f, q[1] = p0.y + (p1.y - p0.y) * f, q[2] = p0.z + (p1.z - p0.z) * f;
            q[3] = nx, q[4] = ny, q[5] = nz;
            q[6] = ty * nz - tz * ny, q[7] = tz * nx - tx * nz, q[8] = tx * ny - ty * nx;
        }
    }
};

Resolved resolve(const CurlParams& p)
{
    Resolved r;
    r.preset = &preset_of(p);
    r.tiers = curl_shape_tiers(p);
    r.table = ShapeTable(p.shape);
    if (p.amplitude.lo == 0.0f && p.amplitude.hi == 0.0f) {
        const float a = curl_default_radius(p);
        r.amplitude = {0.8f * a, 1.2f * a};  // +-20% around the type's radius: our choice
    }
    else {
        r.amplitude = p.amplitude;
    }
    r.amplitude_mid = 0.5f * (r.amplitude.lo + r.amplitude.hi);
    return r;
}

/// Count pass: a curve's frequency (a per-curve draw) and length fix its output point count.
CurveSetup setup_curve(const CurlParams& params, const Resolved& res, std::span<const float3> in, uint64_t id)
{
    CurveSetup setup;
    const double len = in.size() >= 2 ? double(polyline_length(in)) : 0.0;
    Rng rng(params.seed, id, kStreamCurve);
    const bool freq_default = params.frequency.lo == 0.0f && params.frequency.hi == 0.0f;
    setup.frequency = freq_default ? res.preset->ratio / res.amplitude_mid : rng.uniform(params.frequency.lo, params.frequency.hi);
    if (!(len > 0.0)) {
        setup.points = int64_t(in.size());
        return setup;
    }
    const double want = std::ceil(len * double(setup.frequency) * double(params.samples)) + 1.0;
    // Clamped before the integer conversion so absurd frequencies reach the limit check.
    setup.points = std::max<int64_t>(int64_t(in.size()), int64_t(std::min(want, double(kMaxPoints))));
    return setup;
}

/// The centreline of input curve `in` with `n` points: a Catmull-Rom through it (smooth even for
/// coarse guides), resampled evenly in arc length.
void build_centreline(std::span<const float3> in, int64_t n, Centreline& cl)
{
    const int64_t m = int64_t(in.size());
    if (m >= 4) {
        const int per_segment = int(std::clamp<int64_t>((n + m - 2) / (m - 1), 1, 64));
        evaluate_cubic(in, CubicBasis::CatmullRom, true, per_segment, cl.spline);
        resample_by_count(cl.spline, int(n), cl.points, cl.cumulative);
    }
    else {
        resample_by_count(in, int(n), cl.points, cl.cumulative);
    }
    rotation_minimising_frames(cl.points, {1, 0, 0}, cl.frames, cl.tangents);
    cl.length = polyline_length(cl.points);
    cl.ds = cl.length / double(n - 1);
}

/// One curve's draws (Sec. 3.1): its frequency and phase, and per cycle a shape, an amplitude and an
/// offset of the cross-section's centre.
struct CurveDraws {
    float frequency = 0.0f;
    float cos_phase = 1.0f, sin_phase = 0.0f;
    std::vector<Cycle> cycles;
};

/// The draws of curve `id` (frequency from the count pass), enough cycles for `centre_len`.
void draw_curve(const CurlParams& params, const Resolved& res, uint64_t id, float frequency, double centre_len, CurveDraws& d)
{
    Rng curve_rng(params.seed, id, kStreamCurve);
    curve_rng.next_u64();  // the frequency draw (count pass)
    d.frequency = frequency;
    const float phase = curve_rng.uniform(params.phase.lo, params.phase.hi);
    const float angle = 2.0f * std::numbers::pi_v<float> * phase;
    d.cos_phase = std::cos(angle);
    d.sin_phase = std::sin(angle);
    const double curl_len = std::max(0.0, centre_len - double(params.root_ease));
    const int64_t ncycles = std::max<int64_t>(1, int64_t(std::floor(curl_len * double(frequency))) + 2);
    d.cycles.resize(size_t(ncycles));
    const Rng shape_rng(params.seed, id, kStreamShape), amp_rng(params.seed, id, kStreamAmp), offset_rng(params.seed, id, kStreamOffset);
    auto unit = [](uint64_t v) { return double(v >> 11) * (1.0 / 9007199254740992.0); };
    const bool offsets = params.offset.hi > 0.0f;  // else every centre stays on the centreline (the default)
    for (int64_t k = 0; k < ncycles; ++k) {
        Cycle& cy = d.cycles[size_t(k)];
        cy.shape = pick_curl_shape(res.tiers, unit(shape_rng.at(uint64_t(k))));
        cy.amplitude = res.amplitude.lo + (res.amplitude.hi - res.amplitude.lo) * float(unit(amp_rng.at(uint64_t(k))));
        if (!offsets) {
            cy.ox = cy.oy = 0.0f;
            continue;
        }
        const float orad = params.offset.lo + (params.offset.hi - params.offset.lo) * float(unit(offset_rng.at(2 * uint64_t(k))));
        const float oang = 2.0f * std::numbers::pi_v<float> * float(unit(offset_rng.at(2 * uint64_t(k) + 1)));
        cy.ox = orad * std::cos(oang);
        cy.oy = orad * std::sin(oang);
    }
}

/// Cycle coordinate at centreline arc length s: 0 where the curl starts, after the root ease.
double cycle_u(const CurveDraws& d, const CurlParams& p, double s) { return double(d.frequency) * (s - double(p.root_ease)); }

/// The curl's offsets in the cross-section plane at many points of a curve at once (x along the
/// frame normal, y along the binormal, the root envelope applied), and the scratch they are made in.
/// Sec. 3.1: each cycle takes its own shape; around each join the two neighbouring cycles' closed
/// curves are cross-faded with a C1 smoothstep, so position and tangent stay continuous (both shapes
/// are smooth at t = 0, see curl_shapes.h). The points of one cycle are evaluated together (its
/// shape's sines and cosines four at a time), then the joins' other cycles, then the blend: one
/// point at a time, through a call per point, this was a third of the op (perf, curl_bench).
struct CurlOffsets {
    std::vector<float> x, y, env;
    std::vector<int64_t> cycle;
    std::vector<float> t;
    // The points near a join: their index, the other cycle, its parameter, the weight of their own.
    std::vector<uint32_t> join_index;
    std::vector<int64_t> join_cycle;
    std::vector<float> join_t, join_weight, join_x, join_y;

    /// Offsets at cycle coordinates u[0..m) (u = 0 where the curl starts; non-decreasing, as the
    /// points walk up the curve) into x, y, and the envelope into env.
    void evaluate(const CurveDraws& d, const CurlParams& p, const ShapeTable& table, const double* u, size_t m)
    {
        x.resize(m), y.resize(m), env.resize(m), cycle.resize(m), t.resize(m);
        const int64_t count = int64_t(d.cycles.size()), last = count - 1;
        for (size_t i = 0; i < m; ++i) {
            const int64_t k = cycle_of(u[i], count);
            cycle[i] = k;
            t[i] = float(u[i] - double(k));  // in [0, 1) inside the curl; negative before it, > 1 past the end
            env[i] = root_envelope(u[i], p.root_ramp);
        }
        cycles(d, table, cycle.data(), t.data(), m, x.data(), y.data());
        if (p.blend > 0.0f) {
            const float blend = p.blend;
            join_index.clear(), join_cycle.clear(), join_t.clear(), join_weight.clear();
            for (size_t i = 0; i < m; ++i) {
                const float ti = t[i];
                const int64_t k = cycle[i];
                if (ti < blend && k > 0) {
                    join_cycle.push_back(k - 1), join_t.push_back(ti + 1.0f);
                    join_weight.push_back(smoothstep((ti + blend) / (2.0f * blend)));
                }
                else if (ti > 1.0f - blend && k < last) {
                    join_cycle.push_back(k + 1), join_t.push_back(ti - 1.0f);
                    join_weight.push_back(1.0f - smoothstep((ti - (1.0f - blend)) / (2.0f * blend)));
                }
                else {
                    continue;
                }
                join_index.push_back(uint32_t(i));
            }
            const size_t joins = join_index.size();
            join_x.resize(joins), join_y.resize(joins);
            cycles(d, table, join_cycle.data(), join_t.data(), joins, join_x.data(), join_y.data());
            for (size_t q = 0; q < joins; ++q) {
                const size_t i = join_index[q];
                const float w = join_weight[q];
                x[i] = w * x[i] + (1.0f - w) * join_x[q];
                y[i] = w * y[i] + (1.0f - w) * join_y[q];
            }
        }
        for (size_t i = 0; i < m; ++i) x[i] = env[i] * x[i], y[i] = env[i] * y[i];
    }

    /// The curled point i from its centre c and frame (n, b): where the envelope is 0, c itself.
    float3 point(size_t i, const float3& c, const float3& n, const float3& b) const
    {
        return env[i] == 0.0f ? c : c + n * x[i] + b * y[i];
    }

private:
    /// Each cycle's own cross-section at t[i] (cycle[i] non-decreasing): centre + amplitude x the
    /// phase's rotation of its shape.
    static void cycles(const CurveDraws& d, const ShapeTable& table, const int64_t* cycle, const float* t, size_t m, float* x, float* y)
    {
        for (size_t i = 0; i < m;) {
            size_t j = i + 1;
            while (j < m && cycle[j] == cycle[i]) ++j;
            const Cycle& cy = d.cycles[size_t(cycle[i])];
            curl_shape_points(cy.shape, table, t + i, j - i, x + i, y + i);
            for (size_t q = i; q < j; ++q) {
                const float sx = cy.amplitude * x[q], sy = cy.amplitude * y[q];
                x[q] = cy.ox + d.cos_phase * sx - d.sin_phase * sy;
                y[q] = cy.oy + d.sin_phase * sx + d.cos_phase * sy;
            }
            i = j;
        }
    }
};

/// What curl_curve keeps from curve to curve (a worker's).
struct CurlScratch {
    std::vector<float3> grid;
    std::vector<double> chord, short_by;
    std::vector<int32_t> lo, hi;
    std::vector<float> frac, at;
    std::vector<uint8_t> far;
    std::vector<double> u;
    CurlOffsets offsets;
};

/// Curls the centreline over arc lengths [0, end] with as many points as it has, evenly spaced:
/// out[j], and its centreline arc length s_of[j].
void curl_prefix(const Centreline& cl, const CurveDraws& d, const CurlParams& p, const ShapeTable& table, double end, CurlScratch& w,
                 std::vector<float3>& out, std::vector<double>& s_of)
{
    const int64_t n = int64_t(cl.points.size());
    const double ds2 = end / double(n - 1);
    w.u.resize(size_t(n));
    for (int64_t j = 0; j < n; ++j) {
        s_of[size_t(j)] = double(j) * ds2;
        w.u[size_t(j)] = cycle_u(d, p, s_of[size_t(j)]);
    }
    cl.frames_at(s_of, w.lo, w.hi, w.frac, w.at, w.far);
    w.offsets.evaluate(d, p, table, w.u.data(), size_t(n));
    for (int64_t j = 0; j < n; ++j) {
        const float* q = w.at.data() + 9 * j;
        out[size_t(j)] = w.offsets.point(size_t(j), {q[0], q[1], q[2]}, {q[3], q[4], q[5]}, {q[6], q[7], q[8]});
    }
}

/// Where the curled polyline of pass 2 (n points evenly over centreline arc lengths [0, s_end])
/// will reach the input's length, predicted from pass 1, which sampled the curl on the centreline's
/// own grid, k = length / s_end times coarser. A chord c whose ends bend by the second difference D
/// falls short of its arc by about |D|^2 / (24 c) (the arc's a^3 kappa^2 / 24 with |D| = kappa a^2);
/// split into k chords it falls short by 1/k^2 of that. Predicting pass 2's length this way, rather
/// than taking pass 1's cut, spares the one or two corrective passes that cut needed (pass 2 then
/// measured longer than pass 1 on tight curls; curl_prefix was a third of curl_bench, perf).
double predicted_cut(std::span<const double> chord, std::span<const double> short_by, double in_len, double ds, double length)
{
    double s_end = -1.0;
    // k depends on the cut it predicts: start from the chords' own cut, refine once.
    double k2 = 0.0;
    for (int round = 0; round < 3; ++round) {
        const double keep = k2 > 0.0 ? 1.0 - 1.0 / k2 : 0.0;
        double acc = 0.0, cut = -1.0;
        for (size_t j = 0; j < chord.size(); ++j) {
            const double seg = chord[j] + keep * short_by[j];
            if (acc + seg >= in_len) {
                cut = (double(j) + (seg > 0.0 ? (in_len - acc) / seg : 0.0)) * ds;
                break;
            }
            acc += seg;
        }
        if (cut <= 0.0) return s_end;
        s_end = cut;
        const double k = length / s_end;
        k2 = k * k;
    }
    return s_end;
}

/// The curled curve: as many points as the centreline into `out`, their centreline arc lengths into
/// `s_of` (`w`: scratch). Pass 1 curls the centreline on its own grid,
/// and (Sec. 3.1 says nothing of length; real curls shrink, the curl index) predicts where the curled
/// hair reaches the input's length `in_len`: it then covers only that part of its centreline, which
/// pass 2 re-samples with all the points. Without length preservation pass 1 is the result.
void curl_curve(const Centreline& cl, const CurveDraws& d, const CurlParams& p, const ShapeTable& table, double in_len, CurlScratch& w,
                std::vector<float3>& out, std::vector<double>& s_of)
{
    std::vector<float3>& grid = w.grid;
    std::vector<double>&chord = w.chord, &short_by = w.short_by;
    const int64_t n = int64_t(cl.points.size());
    grid.resize(size_t(n));
    chord.clear();
    short_by.clear();
    double acc = 0.0;
    int64_t evaluated = n;
    // A chunk of points at a time (the offsets are made together), until the chords reach in_len.
    const int64_t chunk = p.preserve_length ? 64 : n;
    for (int64_t j0 = 0; j0 < n && evaluated == n; j0 += chunk) {
        const int64_t j1 = std::min(n, j0 + chunk);
        w.u.resize(size_t(j1 - j0));
        for (int64_t j = j0; j < j1; ++j) w.u[size_t(j - j0)] = cycle_u(d, p, double(j) * cl.ds);
        w.offsets.evaluate(d, p, table, w.u.data(), size_t(j1 - j0));
        for (int64_t j = j0; j < j1; ++j) {
            grid[size_t(j)] = w.offsets.point(size_t(j - j0), cl.points[size_t(j)], cl.frames[size_t(j)].n, cl.frames[size_t(j)].b);
        }
        if (!p.preserve_length) continue;
        for (int64_t j = std::max<int64_t>(j0, 1); j < j1; ++j) {
            chord.push_back(distance(grid[size_t(j - 1)], grid[size_t(j)]));
            acc += chord.back();
            // Past the chords' own cut pass 2 cannot reach: its chords are longer.
            if (acc >= in_len) {
                evaluated = j + 1;
                break;
            }
        }
    }
    // Each chord's bend: the mean of the squared second differences at its two ends, where they
    // exist (each point's once: short_by holds them until it holds the chords' shortfalls).
    const size_t nc = chord.size();
    short_by.resize(nc);
    auto bend = [&](size_t m) { return double(length_squared(grid[m - 1] - grid[m] * 2.0f + grid[m + 1])); };
    double before = 0.0;  // the bend at chord i's first end (point i), where it exists
    for (size_t i = 0; i < nc; ++i) {
        const bool at_start = i >= 1, at_end = int64_t(i) + 2 < evaluated;
        const double after = at_end ? bend(i + 1) : 0.0;
        const int count = int(at_start) + int(at_end);
        const double sum = at_start ? (at_end ? before + after : before) : after;
        short_by[i] = count > 0 && chord[i] > 0.0 ? sum / double(count) / (24.0 * chord[i]) : 0.0;
        before = after;
    }
    out.resize(size_t(n));
    s_of.resize(size_t(n));
    double s_end = p.preserve_length ? predicted_cut(chord, short_by, in_len, cl.ds, cl.length) : -1.0;
    if (!(s_end > 0.0 && s_end < cl.length)) {
        out = grid;
        for (int64_t j = 0; j < n; ++j) s_of[size_t(j)] = double(j) * cl.ds;
        return;
    }
    curl_prefix(cl, d, p, table, s_end, w, out, s_of);
    // Correct the cut on pass 2's own polyline (at most twice) until the length is within 0.2%.
    for (int iter = 0; iter < 2; ++iter) {
        double len = 0.0, cut = -1.0;
        for (int64_t j = 1; j < n; ++j) {
            const double seg = distance(out[size_t(j - 1)], out[size_t(j)]);
            if (cut < 0.0 && len + seg >= in_len) {
                cut = s_of[size_t(j - 1)] + (seg > 0.0 ? (in_len - len) / seg : 0.0) * (s_of[size_t(j)] - s_of[size_t(j - 1)]);
            }
            len += seg;
        }
        if (std::fabs(len - in_len) <= 2e-3 * in_len) break;
        s_end = cut >= 0.0 ? cut : std::min(cl.length, s_end * in_len / std::max(len, 1e-30));
        curl_prefix(cl, d, p, table, s_end, w, out, s_of);
    }
}

}  // namespace

float curl_default_radius(const CurlParams& params) { return preset_of(params).radius_cm * params.units_per_cm; }

void CurlParams::validate_for(const std::string& op) const
{
    try {
        validate();
    }
    catch (const InvalidParam& e) {
        const std::string message = e.what();
        throw InvalidParam(message.rfind("curl: ", 0) == 0 ? op + ": " + message.substr(6) : message);
    }
}

void CurlParams::validate() const
{
    preset_of(*this);
    if (!(uniformity >= 0.0f && uniformity <= 1.0f)) {
        throw InvalidParam("curl: `uniformity` must be in [0, 1] (got " + num(uniformity) + ")");
    }
    if (dominant < -1 || dominant >= curl_shape_count()) {
        throw InvalidParam("curl: `dominant` must be one of " + curl_shape_list() + " (got " + std::to_string(dominant) + ")");
    }
    for (size_t i = 0; i < shapes.size(); ++i) {
        if (shapes[i] < 0 || shapes[i] >= curl_shape_count()) {
            throw InvalidParam("curl: `shapes` entries must be among " + curl_shape_list() + " (got " + std::to_string(shapes[i]) + ")");
        }
        for (size_t j = 0; j < i; ++j) {
            if (shapes[j] == shapes[i]) {
                throw InvalidParam("curl: `shapes` lists " + std::string(curl_shape_name(shapes[i])) + " twice");
            }
        }
    }
    const bool amp_default = amplitude.lo == 0.0f && amplitude.hi == 0.0f;
    if (!finite(amplitude) || (!amp_default && !(amplitude.lo >= 0.0f && amplitude.hi > 0.0f && amplitude.lo <= amplitude.hi))) {
        throw InvalidParam("curl: `amplitude` must be lo,hi with 0 <= lo <= hi and hi > 0, scene units (got " + range_text(amplitude) + ")");
    }
    const bool freq_default = frequency.lo == 0.0f && frequency.hi == 0.0f;
    if (!finite(frequency) || (!freq_default && !(frequency.lo > 0.0f && frequency.lo <= frequency.hi))) {
        throw InvalidParam("curl: `frequency` must be lo,hi with 0 < lo <= hi, cycles per scene unit (got " + range_text(frequency) + ")");
    }
    if (!finite(phase) || !(phase.lo <= phase.hi)) {
        throw InvalidParam("curl: `phase` must be lo,hi with lo <= hi, turns (got " + range_text(phase) + ")");
    }
    if (!finite(offset) || !(offset.lo >= 0.0f && offset.lo <= offset.hi)) {
        throw InvalidParam("curl: `offset` must be lo,hi with 0 <= lo <= hi, scene units (got " + range_text(offset) + ")");
    }
    if (!(units_per_cm > 0.0f) || !std::isfinite(units_per_cm)) {
        throw InvalidParam("curl: `units_per_cm` must be > 0 (got " + num(units_per_cm) + ")");
    }
    if (!(root_ease >= 0.0f) || !std::isfinite(root_ease)) {
        throw InvalidParam("curl: `root_ease` must be >= 0, scene units (got " + num(root_ease) + ")");
    }
    if (!(root_ramp >= 0.0f) || !std::isfinite(root_ramp)) {
        throw InvalidParam("curl: `root_ramp` must be >= 0, cycles (got " + num(root_ramp) + ")");
    }
    if (samples < 4 || samples > 256) {
        throw InvalidParam("curl: `samples` must be in 4..256 points per cycle (got " + std::to_string(samples) + ")");
    }
    if (!(blend >= 0.0f && blend < 0.5f)) {
        throw InvalidParam("curl: `blend` must be in [0, 0.5) cycles (got " + num(blend) + ")");
    }
    shape.validate();
    widths.validate("curl");
    curl_shape_tiers(*this);  // the dominant must be allowed, and U < 1 needs another shape
}

CurlShapeTiers curl_shape_tiers(const CurlParams& p)
{
    const HairTypePreset& preset = preset_of(p);
    CurlShapeTiers t;
    t.dominant = p.dominant >= 0 ? p.dominant : preset.dominant;
    std::vector<int> allowed = p.shapes;
    if (allowed.empty()) {
        for (int i = 0; i < curl_shape_count(); ++i) allowed.push_back(i);
    }
    auto is_allowed = [&](int s) { return std::find(allowed.begin(), allowed.end(), s) != allowed.end(); };
    if (!is_allowed(t.dominant)) {
        throw InvalidParam("curl: `dominant` " + std::string(curl_shape_name(t.dominant)) +
                           (p.dominant < 0 ? " (the default of type " + p.hair_type + ")" : std::string()) +
                           " is not among the allowed `shapes`");
    }
    for (int s : preset.secondary) {
        if (s != t.dominant && is_allowed(s)) t.secondary.push_back(s);
    }
    for (int s : allowed) {
        if (s != t.dominant && std::find(t.secondary.begin(), t.secondary.end(), s) == t.secondary.end()) t.rest.push_back(s);
    }
    if (p.uniformity < 1.0f && t.secondary.empty() && t.rest.empty()) {
        throw InvalidParam("curl: `uniformity` " + num(p.uniformity) + " leaves " + num(1.0 - p.uniformity) +
                           " of the cycles to other shapes, but `shapes` allows only " + std::string(curl_shape_name(t.dominant)) +
                           " (use `uniformity` 1 or allow more shapes)");
    }
    const double u = p.uniformity, rest = 1.0 - u;
    const double share_b = t.secondary.empty() ? 0.0 : (t.rest.empty() ? rest : rest * kCurlTierBShare);
    const double share_c = t.rest.empty() ? 0.0 : rest - share_b;
    t.probability.assign(size_t(curl_shape_count()), 0.0);
    t.probability[size_t(t.dominant)] = u;
    t.order.push_back(t.dominant);
    for (int s : t.secondary) {
        t.probability[size_t(s)] = share_b / double(t.secondary.size());
        t.order.push_back(s);
    }
    for (int s : t.rest) {
        t.probability[size_t(s)] = share_c / double(t.rest.size());
        t.order.push_back(s);
    }
    double sum = 0.0;
    for (int s : t.order) {
        sum += t.probability[size_t(s)];
        t.cumulative.push_back(sum);
    }
    t.cumulative.front() = u;  // exactly U for tier A, whatever the rounding of the others
    t.cumulative.back() = 1.0;
    return t;
}

int pick_curl_shape(const CurlShapeTiers& tiers, double x)
{
    for (size_t i = 0; i < tiers.order.size(); ++i) {
        if (x < tiers.cumulative[i]) return tiers.order[i];
    }
    return tiers.order.back();
}

namespace {

/// What every block of one run shares: the resolved parameters and, per input curve, its output
/// point count and frequency (a curve's draws depend only on its id, never on its block).
struct CurlPlan {
    Resolved res;
    std::vector<int64_t> counts;
    std::vector<float> frequency;
    int64_t largest = 0;  ///< the most points of one output curve
    bool gather = false;  ///< other point attributes are taken from the nearest input point
};

/// The count pass over every curve, and the output's size checked against the point limit.
CurlPlan plan_curl(const CurveSet& src, const CurlParams& params)
{
    params.validate();
    CurlPlan plan;
    plan.res = resolve(params);
    const auto P = src.positions();
    const size_t nc = src.num_curves();
    plan.counts.resize(nc);
    plan.frequency.resize(nc);
    parallel_for(int64_t(nc), 256, [&](int64_t b, int64_t e) {
        const std::vector<int64_t> ids = src.curve_ids(size_t(b), size_t(e));
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = src.points_of(size_t(c));
            const CurveSetup s = setup_curve(params, plan.res, P.subspan(size_t(r.begin), size_t(r.size())), uint64_t(ids[size_t(c - b)]));
            plan.counts[size_t(c)] = s.points;
            plan.frequency[size_t(c)] = s.frequency;
        }
    });
    int64_t total = 0, largest = 0;
    for (const int64_t n : plan.counts) total += n, largest = std::max(largest, n);
    if (total >= kMaxPoints) {
        throw LimitExceeded("curl: the output would have " + std::to_string(total) + " points (limit " + std::to_string(kMaxPoints) +
                            "); lower `samples` or `frequency`");
    }
    plan.largest = largest;
    for (const Attribute& a : src.attributes(Domain::Point).all()) {
        if (a.name != attr::P && a.name != attr::width && a.name != "shape" && a.name != "cycle") plan.gather = true;
    }
    return plan;
}

/// Before allocating (a curve 1.7e7 units long asked for 5e8 points and was killed past 2 GB: op
/// fuzzer): the output copies every point column of the input and adds shape, cycle and width; a
/// worker's centreline holds a curve's points and frames. `at_once`: output points held at once
/// (all of them, or a block's when the output is handed over a block at a time).
void check_curl_memory(const CurveSet& src, const CurlParams& params, const CurlPlan& plan, int64_t at_once)
{
    check_memory("curl: " + std::to_string(at_once) + " output points held (curve length x `frequency` x `samples`)",
                 double(at_once) * (bytes_per_point(src) + (params.labels ? 12.0 : 4.0)) + double(plan.largest) * 64.0,
                 "lower `frequency` or `samples`");
}

/// Curves [c0, c1) of `src`, curled: the output of those curves alone.
CurveSet curl_range(const CurveSet& src, const CurlParams& params, const CurlPlan& plan, int64_t c0, int64_t c1, const Surface* scalp,
                    const ProgressStep& step)
{
    const auto P = src.positions();
    const auto src_width = src.find<float>(Domain::Point, attr::width);
    const std::vector<int64_t> ids = src.curve_ids(size_t(c0), size_t(c1));
    CurveSet dst = CurveSet::from_counts(std::span<const int64_t>(plan.counts).subspan(size_t(c0), size_t(c1 - c0)));
    auto dP = dst.positions_for_write();
    std::span<int32_t> dshape, dcycle;
    if (params.labels) {
        dshape = dst.add<int32_t>(Domain::Point, "shape");
        dcycle = dst.add<int32_t>(Domain::Point, "cycle");
    }
    // Widths the output is tapered to are written curve by curve, each as it is made; else the
    // input's are interpolated.
    const std::optional<HairWidths> taper = hair_widths_taper(src, params.widths, params.units_per_cm);
    const bool carry_width = !taper && !src_width.empty();
    std::span<float> dwidth;
    if (taper || carry_width) dwidth = dst.add<float>(Domain::Point, attr::width);
    const bool gather = plan.gather;
    std::vector<int64_t> src_point(gather ? dst.num_points() : 0);

    parallel_for(c1 - c0, 64, [&](int64_t b, int64_t e) {
        Centreline cl;
        CurveDraws draws;
        CurlScratch scratch;
        std::vector<float3> out;
        std::vector<double> in_cum, s_of, taper_scratch;
        auto write_taper = [&](const IndexRange& d) {
            if (taper) {
                taper_curve_widths(dP.subspan(size_t(d.begin), size_t(d.size())), dwidth.subspan(size_t(d.begin), size_t(d.size())), *taper->root,
                                   *taper->tip, taper_scratch);
            }
        };
        for (int64_t k = b; k < e; ++k) {
            const int64_t c = c0 + k;
            const IndexRange r = src.points_of(size_t(c));
            const IndexRange d = dst.points_of(size_t(k));
            const auto in = P.subspan(size_t(r.begin), size_t(r.size()));
            cumulative_lengths(in, in_cum);
            const double in_len = in_cum.empty() ? 0.0 : in_cum.back();
            if (!(in_len > 0.0) || r.size() < 2) {
                // Nothing to curl: the curve passes through unchanged.
                for (int64_t i = 0; i < d.size(); ++i) {
                    dP[size_t(d.begin + i)] = in[size_t(i)];
                    if (params.labels) {
                        dshape[size_t(d.begin + i)] = plan.res.tiers.dominant;
                        dcycle[size_t(d.begin + i)] = 0;
                    }
                    if (carry_width) dwidth[size_t(d.begin + i)] = src_width[size_t(r.begin + i)];
                    if (gather) src_point[size_t(d.begin + i)] = r.begin + i;
                }
                write_taper(d);
                step.advance(1);
                continue;
            }

            const int64_t n = d.size();
            build_centreline(in, n, cl);
            draw_curve(params, plan.res, uint64_t(ids[size_t(k)]), plan.frequency[size_t(c)], cl.length, draws);
            curl_curve(cl, draws, params, plan.res.table, in_len, scratch, out, s_of);

            if (scalp) {
                // No curled point inside the scalp (fields/keep_outside.h): pulled back toward its
                // centreline point while that is outside, which keeps the curl's direction, else moved
                // out with a margin of a thousandth of the curl, doubled on each of up to 12 tries (in a
                // crease each step along the band's normal gains only about half of what is missing:
                // four tries left 821 of Sintel's 3.2 M curled points up to 0.07 inside at the ear).
                const KeepOutside rule{0.0f, 1e-3f * std::max(plan.res.amplitude_mid, 1e-6f), 12};
                for (int64_t j = 0; j < n; ++j) {
                    const float3 anchor = cl.point_at(s_of[size_t(j)]);
                    keep_outside(out[size_t(j)], *scalp, rule, 0.0f, &anchor);
                }
            }

            const double to_input = cl.length > 0.0 ? in_len / cl.length : 0.0;
            const int64_t ncycles = int64_t(draws.cycles.size());
            size_t cursor = 0;  // the points walk up the curve: each lookup goes on from the last
            for (int64_t j = 0; j < n; ++j) {
                const size_t o = size_t(d.begin + j);
                dP[o] = out[size_t(j)];
                if (params.labels) {
                    const double u = cycle_u(draws, params, s_of[size_t(j)]);
                    const int64_t k = cycle_of(u, ncycles);
                    dcycle[o] = int32_t(k);
                    dshape[o] = draws.cycles[size_t(k)].shape;
                }
                if (carry_width || gather) {
                    // Where this point's centreline position falls on the input curve, by arc length.
                    const ArcSpot a = locate_at_length(in_cum, s_of[size_t(j)] * to_input, cursor);
                    if (carry_width) {
                        dwidth[o] = float((1.0 - a.t) * src_width[size_t(r.begin) + a.lo] + a.t * src_width[size_t(r.begin) + a.hi]);
                    }
                    if (gather) src_point[o] = r.begin + int64_t(a.nearest);
                }
            }
            write_taper(d);
            step.advance(1);
        }
    });

    dst.set_detail_string("hair_type", plan.res.preset->name);
    std::vector<int64_t> curves(src.attributes(Domain::Curve).count() > 0 ? size_t(c1 - c0) : 0);  // read only for curve columns
    for (size_t k = 0; k < curves.size(); ++k) curves[k] = c0 + int64_t(k);
    carry_curve_attributes(src, dst, curves);
    if (gather) carry_point_attributes(src, dst, src_point, {attr::P, attr::width, "shape", "cycle"});
    if (taper) {
        dst.attributes(Domain::Curve).remove(attr::width);  // as taper_widths does: the per-point taper replaces it
    }
    else {
        apply_hair_widths(dst, params.widths, params.units_per_cm);
    }
    return dst;
}

}  // namespace

CurveSet curl(const CurveSet& src, const CurlParams& params, const Surface* scalp, Progress* progress)
{
    const CurlPlan plan = plan_curl(src, params);
    int64_t total = 0;
    for (const int64_t n : plan.counts) total += n;
    check_curl_memory(src, params, plan, total);
    const int64_t nc = int64_t(src.num_curves());
    const ProgressStep step(progress, "curl", nc);
    return curl_range(src, params, plan, 0, nc, scalp, step);
}

void curl_blocks(const CurveSet& src, const CurlParams& params, const Surface* scalp, Progress* progress, int64_t block_points,
                 const std::function<void(std::span<const int64_t> counts)>& start, const std::function<void(const CurveSet& block)>& emit)
{
    const CurlPlan plan = plan_curl(src, params);
    const std::vector<int64_t> ends = curve_block_ends(plan.counts, block_points);
    check_curl_memory(src, params, plan, largest_curve_block(plan.counts, ends));
    start(plan.counts);
    const ProgressStep step(progress, "curl", int64_t(src.num_curves()));
    hand_over_curve_blocks(ends, [&](int64_t c0, int64_t c1) { return curl_range(src, params, plan, c0, c1, scalp, step); }, emit);
}

}  // namespace groom
