// From composed curves prims (usda_syntax.h) to one CurveSet: counts and points checked, cubic and NURBS
// curves evaluated into polylines, primvars mapped to columns by interpolation, points taken to world
// space, every prim concatenated in traversal order. Kept apart from parsing and composition because it
// is geometry, not syntax; read_usda, which runs all three, is here.
//
// Every output point is a fixed linear combination of control points (a "stencil"): the basis weights
// of its segment at its parameter, phantom end points of pinned curves folded in, rational NURBS
// weights divided out. Positions and vertex primvars go through the same stencil, varying primvars
// through a linear one over segment ends, so every basis and wrap shares one code path.
#include "kernel/io/formats.h"
#include "kernel/io/usda_syntax.h"
#include "kernel/units.h"

#include <algorithm>
#include <cmath>

namespace groom::io {

namespace usda {
namespace {

/// Output point p = sum over [offsets[p], offsets[p+1]) of weight[i] * value[index[i]].
struct Stencil {
    std::vector<int64_t> offsets{0};
    std::vector<int64_t> index;
    std::vector<double> weight;
    void add(int64_t i, double w)
    {
        index.push_back(i);
        weight.push_back(w);
    }
    void end_point() { offsets.push_back(static_cast<int64_t>(index.size())); }
    size_t size() const { return offsets.size() - 1; }
};

/// The evaluated topology of one prim: output counts, the stencils of vertex and varying values.
struct Evaluation {
    std::vector<int64_t> counts;
    Stencil vertex, varying;
    int64_t num_varying = 0;  ///< how many varying values the prim must author
};

/// A control point of an extended (pinned / periodic) curve: one or two real control points.
struct Cv {
    int64_t a, b;
    double wa, wb;
};

void basis_weights(const std::string& basis, double t, double w[4])
{
    const double s = 1 - t, t2 = t * t, t3 = t2 * t;
    if (basis == "bezier") {
        w[0] = s * s * s, w[1] = 3 * t * s * s, w[2] = 3 * t2 * s, w[3] = t3;
    }
    else if (basis == "bspline") {
        w[0] = s * s * s / 6, w[1] = (3 * t3 - 6 * t2 + 4) / 6, w[2] = (-3 * t3 + 3 * t2 + 3 * t + 1) / 6, w[3] = t3 / 6;
    }
    else {  // catmullRom
        w[0] = 0.5 * (-t3 + 2 * t2 - t), w[1] = 0.5 * (3 * t3 - 5 * t2 + 2), w[2] = 0.5 * (-3 * t3 + 4 * t2 + t), w[3] = 0.5 * (t3 - t2);
    }
}

/// BasisCurves: linear or cubic (bezier vstep 3, bspline and catmullRom vstep 1), nonperiodic, periodic
/// or pinned, per UsdGeomBasisCurves: segments = (n - 4) / vstep + 1 nonperiodic, n / vstep periodic,
/// (n - 2) / vstep + 1 pinned (bezier is already pinned); varying values = segments + 1, or segments when
/// periodic. A periodic curve is closed by repeating its first point at the end.
Evaluation evaluate_basis_curves(const std::vector<int32_t>& counts, const std::string& type, const std::string& basis, const std::string& wrap,
                                 int k, const std::string& where)
{
    if (type != "linear" && type != "cubic") throw ParseError(where + ": curve type '" + type + "' is not supported (expected linear or cubic)");
    if (wrap != "nonperiodic" && wrap != "periodic" && wrap != "pinned") {
        throw ParseError(where + ": wrap '" + wrap + "' is not supported (expected nonperiodic, periodic or pinned)");
    }
    const bool cubic = type == "cubic", periodic = wrap == "periodic";
    if (cubic && basis != "bezier" && basis != "bspline" && basis != "catmullRom") {
        throw ParseError(where + ": cubic basis '" + basis + "' is not supported (expected bezier, bspline or catmullRom)");
    }
    Evaluation e;
    int64_t base = 0, vbase = 0;
    for (size_t c = 0; c < counts.size(); ++c) {
        const int64_t n = counts[c];
        if (!cubic) {
            if (n < 1 || (periodic && n < 2)) throw ParseError(where + ": linear curve " + std::to_string(c) + " has " + std::to_string(n) + " points");
            for (int64_t j = 0; j < n + (periodic ? 1 : 0); ++j) {
                e.vertex.add(base + j % n, 1.0), e.vertex.end_point();
                e.varying.add(vbase + j % n, 1.0), e.varying.end_point();
            }
            e.counts.push_back(n + (periodic ? 1 : 0));
            base += n, vbase += n;
            continue;
        }
        const int vstep = basis == "bezier" ? 3 : 1;
        const bool pinned = wrap == "pinned" && vstep == 1;
        const std::string curve = "cubic " + basis + " " + wrap + " curve " + std::to_string(c) + " has " + std::to_string(n) + " points";
        if (vstep == 3) {
            if (periodic && (n < 3 || n % 3 != 0)) throw ParseError(where + ": " + curve + "; periodic bezier needs a multiple of 3 (at least 3)");
            if (!periodic && (n < 4 || (n - 4) % 3 != 0)) throw ParseError(where + ": " + curve + "; bezier needs 3 per segment plus 1 (4, 7, 10...)");
        }
        else if (n < (pinned ? 2 : periodic ? 3 : 4)) {
            throw ParseError(where + ": " + curve + "; it needs at least " + std::to_string(pinned ? 2 : periodic ? 3 : 4));
        }
        std::vector<Cv> ext;
        if (pinned) ext.push_back({base, base + 1, 2.0, -1.0});  // phantom 2 p0 - p1: the curve starts on p0
        for (int64_t j = 0; j < n; ++j) ext.push_back({base + j, base + j, 1.0, 0.0});
        if (pinned) ext.push_back({base + n - 1, base + n - 2, 2.0, -1.0});
        if (periodic)
            for (int64_t j = 0; j < (vstep == 3 ? 1 : 3); ++j) ext.push_back({base + j, base + j, 1.0, 0.0});
        const int64_t segments = (static_cast<int64_t>(ext.size()) - 4) / vstep + 1;
        const int64_t nvary = periodic ? segments : segments + 1;
        auto emit = [&](int64_t s, double t) {
            double w[4];
            basis_weights(basis, t, w);
            for (int q = 0; q < 4; ++q) {
                const Cv& cv = ext[static_cast<size_t>(s * vstep + q)];
                e.vertex.add(cv.a, w[q] * cv.wa);
                if (cv.wb != 0) e.vertex.add(cv.b, w[q] * cv.wb);
            }
            e.vertex.end_point();
            e.varying.add(vbase + s, 1 - t);
            e.varying.add(vbase + (s + 1) % nvary, t);
            e.varying.end_point();
        };
        for (int64_t s = 0; s < segments; ++s)
            for (int i = 0; i < k; ++i) emit(s, static_cast<double>(i) / k);
        emit(segments - 1, 1.0);  // the curve's end (a periodic curve's start again: closed)
        e.counts.push_back(segments * k + 1);
        base += n, vbase += nvary;
    }
    e.num_varying = vbase;
    return e;
}

/// NurbsCurves: each curve's order, its n + order knots, its optional range and point weights; every
/// knot span in the range sampled k times (once for order 2, whose spans are straight), then the
/// range's end. Varying values sit on span ends. Basis functions: The NURBS Book, algorithm A2.2.
/// Orders above this cost order^2 per sample for nothing: DCCs write degree 1 to 7.
constexpr int kMaxOrder = 32;

Evaluation evaluate_nurbs(const std::vector<int32_t>& counts, const PropertyView& props, int k, const std::string& file, const std::string& where)
{
    auto prop = [&](const char* name) -> const Property* {
        const auto it = props.find(name);
        return it == props.end() || it->second->blocked ? nullptr : it->second;
    };
    const Property* order_p = prop("order");
    const Property* knots_p = prop("knots");
    if (!order_p || !order_p->column || !std::holds_alternative<std::vector<int32_t>>(*order_p->column)) {
        throw ParseError(where + " has no 'int[] order'");
    }
    if (!knots_p) throw ParseError(where + " has no 'double[] knots'");
    const auto& order = std::get<std::vector<int32_t>>(*order_p->column);
    const std::vector<double>& knots = knots_p->numbers;
    const Property* ranges_p = prop("ranges");
    const Property* weights_p = prop("pointWeights");
    if (order.size() != counts.size()) {
        fail_at_line(file, order_p->line, "order has " + std::to_string(order.size()) + " values for " + std::to_string(counts.size()) + " curves");
    }
    int64_t total_points = 0, total_knots = 0;
    for (size_t c = 0; c < counts.size(); ++c) {
        if (order[c] < 2 || order[c] > kMaxOrder || counts[c] < order[c]) {
            fail_at_line(file, order_p->line, "curve " + std::to_string(c) + " has order " + std::to_string(order[c]) + " and " + std::to_string(counts[c]) +
                                                  " points; expected order >= 2 and at least order points");
        }
        total_points += counts[c];
        total_knots += counts[c] + order[c];
    }
    if (static_cast<int64_t>(knots.size()) != total_knots) {
        fail_at_line(file, knots_p->line, "knots has " + std::to_string(knots.size()) + " values; the curves need " + std::to_string(total_knots) +
                                              " (points + order per curve)");
    }
    if (ranges_p && ranges_p->numbers.size() != 2 * counts.size()) {
        fail_at_line(file, ranges_p->line, "ranges has " + std::to_string(ranges_p->numbers.size() / 2) + " ranges for " + std::to_string(counts.size()) + " curves");
    }
    if (weights_p && static_cast<int64_t>(weights_p->numbers.size()) != total_points) {
        fail_at_line(file, weights_p->line, "pointWeights has " + std::to_string(weights_p->numbers.size()) + " values for " + std::to_string(total_points) + " points");
    }
    if (weights_p) {
        for (double w : weights_p->numbers)
            if (!(w > 0) || !std::isfinite(w)) fail_at_line(file, weights_p->line, "pointWeights must be positive and finite (found " + format_number(w) + ")");
    }
    Evaluation e;
    int64_t base = 0, kbase = 0, vbase = 0;
    std::vector<double> left, right, N;
    for (size_t c = 0; c < counts.size(); ++c) {
        const int64_t n = counts[c];
        const int m = order[c], p = m - 1;
        const double* U = knots.data() + kbase;
        for (int64_t i = 0; i + 1 < n + m; ++i) {
            if (!(U[i] <= U[i + 1]) || !std::isfinite(U[i + 1])) {
                fail_at_line(file, knots_p->line, "knots of curve " + std::to_string(c) + " decrease or are not finite at knot " + std::to_string(i + 1));
            }
        }
        double a = U[p], b = U[n];
        if (ranges_p) a = ranges_p->numbers[2 * c], b = ranges_p->numbers[2 * c + 1];
        if (!(a < b) || a < U[p] || b > U[n]) {
            fail_at_line(file, ranges_p ? ranges_p->line : knots_p->line, "curve " + std::to_string(c) + ": the range [" + format_number(a) + ", " + format_number(b) +
                                                                      "] is empty or outside the knots' valid span [" + format_number(U[p]) + ", " + format_number(U[n]) + "]");
        }
        auto eval = [&](int64_t span, double u) {
            // Cox-de Boor: the p + 1 basis functions that are non-zero on [U[span], U[span+1]).
            left.assign(m, 0), right.assign(m, 0), N.assign(m, 0);
            N[0] = 1;
            for (int j = 1; j <= p; ++j) {
                left[j] = u - U[span + 1 - j];
                right[j] = U[span + j] - u;
                double saved = 0;
                for (int r = 0; r < j; ++r) {
                    const double denom = right[r + 1] + left[j - r];
                    const double temp = denom != 0 ? N[r] / denom : 0;
                    N[r] = saved + right[r + 1] * temp;
                    saved = left[j - r] * temp;
                }
                N[j] = saved;
            }
            double sum = 0;
            for (int j = 0; j <= p; ++j) sum += N[j] * (weights_p ? weights_p->numbers[base + span - p + j] : 1.0);
            for (int j = 0; j <= p; ++j) {
                const int64_t idx = base + span - p + j;
                e.vertex.add(idx, N[j] * (weights_p ? weights_p->numbers[idx] : 1.0) / sum);
            }
            e.vertex.end_point();
        };
        const int per_span = m == 2 ? 1 : k;
        int64_t samples = 0, spans = 0, last_span = p;
        for (int64_t i = p; i < n; ++i) {
            const double lo = std::max(U[i], a), hi = std::min(U[i + 1], b);
            if (!(lo < hi)) continue;
            for (int j = 0; j < per_span; ++j) {
                eval(i, lo + (hi - lo) * j / per_span);
                e.varying.add(vbase + spans, 1.0 - static_cast<double>(j) / per_span);
                e.varying.add(vbase + spans + 1, static_cast<double>(j) / per_span);
                e.varying.end_point();
                ++samples;
            }
            ++spans;
            last_span = i;
        }
        eval(last_span, b);
        e.varying.add(vbase + spans, 1.0);
        e.varying.end_point();
        e.counts.push_back(samples + 1);
        base += n, kbase += n + m, vbase += spans + 1;
    }
    e.num_varying = vbase;
    return e;
}

AttributeData expand_indexed(const std::string& file, const std::string& name, const Property& values_p, const AttributeData& values_in,
                             const Property& indices_p)
{
    const auto* idx = indices_p.column ? std::get_if<std::vector<int32_t>>(&*indices_p.column) : nullptr;
    if (!idx) fail_at_line(file, indices_p.line, "expected int[] for " + name + ":indices");
    (void)values_p;
    return std::visit(
        [&](const auto& values) -> AttributeData {
            using V = std::decay_t<decltype(values)>;
            V out;
            out.reserve(idx->size());
            for (int32_t i : *idx) {
                if (i < 0 || static_cast<size_t>(i) >= values.size()) {
                    fail_at_line(file, indices_p.line, name + ":indices holds " + std::to_string(i) + ", out of range (" + std::to_string(values.size()) + " values)");
                }
                out.push_back(values[i]);
            }
            return out;
        },
        values_in);
}

size_t data_size(const AttributeData& d)
{
    return std::visit([](const auto& v) { return v.size(); }, d);
}

/// Values through a stencil: real types blended, integers and strings from the heaviest control point.
AttributeData through(const Stencil& st, const AttributeData& src)
{
    return std::visit(
        [&](const auto& v) -> AttributeData {
            using V = std::decay_t<decltype(v)>;
            V out(st.size());
            for (size_t p = 0; p < st.size(); ++p) {
                const int64_t b = st.offsets[p], e = st.offsets[p + 1];
                if (e == b + 1 && st.weight[b] == 1.0) {
                    out[p] = v[st.index[b]];  // a control value as it is: bit exact
                    continue;
                }
                if constexpr (std::is_same_v<V, std::vector<float>>) {
                    double s = 0;
                    for (int64_t i = b; i < e; ++i) s += st.weight[i] * v[st.index[i]];
                    out[p] = static_cast<float>(s);
                }
                else if constexpr (std::is_same_v<V, std::vector<float3>>) {
                    double s[3] = {0, 0, 0};
                    for (int64_t i = b; i < e; ++i) {
                        const float3& q = v[st.index[i]];
                        s[0] += st.weight[i] * q.x, s[1] += st.weight[i] * q.y, s[2] += st.weight[i] * q.z;
                    }
                    out[p] = {static_cast<float>(s[0]), static_cast<float>(s[1]), static_cast<float>(s[2])};
                }
                else {
                    int64_t best = b;
                    for (int64_t i = b; i < e; ++i)
                        if (st.weight[i] > st.weight[best]) best = i;
                    out[p] = v[st.index[best]];
                }
            }
            return out;
        },
        src);
}

/// One composed curves prim as a linear CurveSet in world space.
CurveSet build_prim(const std::string& file, const ComposedCurves& cp, const CurveReadOptions& options, const Warn& warn)
{
    const std::string where = file + ":" + std::to_string(cp.line) + ": " + cp.type_name + " <" + cp.path + ">";
    auto prop = [&](std::string_view name) -> const Property* {
        const auto it = cp.props.find(name);
        return it == cp.props.end() || it->second->blocked ? nullptr : it->second;
    };
    // An animated prim: groom reads one frame a file, so say which one this is.
    if (warn) {
        for (const auto& [pname, pp] : cp.props) {
            if (pp->time_samples > 1) {
                warn(file + ":" + std::to_string(pp->line) + ": " + std::string(pname) + " of <" + cp.path + "> has " +
                     std::to_string(pp->time_samples) + " time samples; read the earliest (time " + format_number(pp->first_time) +
                     "): groom reads one frame a file (guides.####.usda with --frames)");
            }
        }
    }
    const Property* points_p = prop("points");
    const Property* counts_p = prop("curveVertexCounts");
    if (!points_p) throw ParseError(where + " has no 'points'");
    if (!counts_p) throw ParseError(where + " has no 'curveVertexCounts'");
    const auto* pts = points_p->column ? std::get_if<std::vector<float3>>(&*points_p->column) : nullptr;
    if (!pts) fail_at_line(file, points_p->line, "expected point3f[] for 'points' in <" + cp.path + ">, found " + points_p->type);
    std::vector<int32_t> counts;
    if (counts_p->column && std::holds_alternative<std::vector<int32_t>>(*counts_p->column)) {
        counts = std::get<std::vector<int32_t>>(*counts_p->column);
    }
    else if (counts_p->column && std::holds_alternative<std::vector<int64_t>>(*counts_p->column)) {
        for (int64_t v : std::get<std::vector<int64_t>>(*counts_p->column)) counts.push_back(static_cast<int32_t>(std::clamp<int64_t>(v, -1, INT32_MAX)));
    }
    else {
        fail_at_line(file, counts_p->line, "expected int[] for 'curveVertexCounts' in <" + cp.path + ">, found " + counts_p->type);
    }
    int64_t total = 0;
    for (size_t c = 0; c < counts.size(); ++c) {
        if (counts[c] < 0) fail_at_line(file, counts_p->line, "curveVertexCounts[" + std::to_string(c) + "] is negative (" + std::to_string(counts[c]) + ")");
        total += counts[c];
    }
    if (total != static_cast<int64_t>(pts->size())) {
        fail_at_line(file, counts_p->line, "curveVertexCounts sum to " + std::to_string(total) + " but 'points' (line " + std::to_string(points_p->line) + ") has " +
                                               std::to_string(pts->size()) + " points");
    }
    for (size_t i = 0; i < pts->size(); ++i) {
        if (!isfinite((*pts)[i])) fail_at_line(file, points_p->line, "points[" + std::to_string(i) + "] is not finite (NaN, inf, or past float's range of 3.4e38)");
    }
    auto token = [&](const char* name, const char* fallback) -> std::string {
        const Property* p = prop(name);
        if (!p) return fallback;
        const auto* v = p->column ? std::get_if<std::vector<std::string>>(&*p->column) : nullptr;
        if (!v || v->size() != 1) fail_at_line(file, p->line, std::string("expected one token for '") + name + "'");
        return (*v)[0];
    };
    const int k = std::max(options.cubic_samples_per_segment, 1);
    // USD's schema defaults: a BasisCurves prim with no type and basis is cubic bezier.
    const Evaluation ev = cp.type_name == "NurbsCurves"
                              ? evaluate_nurbs(counts, cp.props, k, file, where)
                              : evaluate_basis_curves(counts, token("type", "cubic"), token("basis", "bezier"), token("wrap", "nonperiodic"), k, where);
    const auto num_curves = static_cast<int64_t>(counts.size());

    CurveSet out = CurveSet::from_counts(std::span<const int64_t>(ev.counts));
    {
        // Positions: evaluated in double, then to world space.
        const Matrix4& M = cp.world;
        auto dst = out.positions_for_write();
        const bool identity = M == kIdentity;
        for (size_t p = 0; p < ev.vertex.size(); ++p) {
            const int64_t b = ev.vertex.offsets[p];
            if (identity && ev.vertex.offsets[p + 1] == b + 1 && ev.vertex.weight[b] == 1.0) {
                dst[p] = (*pts)[ev.vertex.index[b]];  // a control point as it is: bit exact, -0 kept
                continue;
            }
            double s[3] = {0, 0, 0};
            for (int64_t i = ev.vertex.offsets[p]; i < ev.vertex.offsets[p + 1]; ++i) {
                const float3& q = (*pts)[ev.vertex.index[i]];
                s[0] += ev.vertex.weight[i] * q.x, s[1] += ev.vertex.weight[i] * q.y, s[2] += ev.vertex.weight[i] * q.z;
            }
            for (int r = 0; r < 3; ++r) {
                const double v = M[r * 4] * s[0] + M[r * 4 + 1] * s[1] + M[r * 4 + 2] * s[2] + M[r * 4 + 3];
                (&dst[p].x)[r] = static_cast<float>(v);
            }
        }
    }
    // Widths scale with the uniform part of the transform: the cube root of its volume change.
    const Matrix4& M = cp.world;
    const double det = M[0] * (M[5] * M[10] - M[6] * M[9]) - M[1] * (M[4] * M[10] - M[6] * M[8]) + M[2] * (M[4] * M[9] - M[5] * M[8]);
    const double width_scale = std::cbrt(std::abs(det));

    // Attributes in the order they were written (the composed view is sorted by name), so a file
    // read and written again, or shards merged, come back byte for byte.
    std::vector<std::pair<std::string_view, const Property*>> authored(cp.props.begin(), cp.props.end());
    std::stable_sort(authored.begin(), authored.end(), [](const auto& a, const auto& b) { return a.second->line < b.second->line; });
    for (const auto& [pname, pp] : authored) {
        const bool is_widths = pname == "widths";
        if (!is_widths && pname.rfind("primvars:", 0) != 0) continue;
        if (pname.size() > 8 && pname.substr(pname.size() - 8) == ":indices") continue;
        if (pp->blocked) continue;
        const std::string label(pname);
        const std::string name = is_widths ? std::string(attr::width) : label.substr(9);
        if (!pp->column) {
            // groom writes a curve's root UV twice: primvars:root_uv (which it reads back) and
            // texCoord2f primvars:st for renderers; the copy is no news to the user.
            if (label == "primvars:st" && cp.props.find(std::string_view("primvars:root_uv")) != cp.props.end()) continue;
            if (warn) warn(file + ":" + std::to_string(pp->line) + ": " + label + " of <" + cp.path + "> (" + pp->type + ") left out: no attribute type holds it");
            continue;
        }
        AttributeData data = *pp->column;
        if (const Property* idx = prop(label + ":indices")) data = expand_indexed(file, label, *pp, data, *idx);
        if (is_widths && !std::holds_alternative<std::vector<float>>(data)) fail_at_line(file, pp->line, "expected float[] for 'widths' in <" + cp.path + ">");
        const auto n = static_cast<int64_t>(data_size(data));
        const int64_t es = pp->element_size;
        std::string interp = pp->interpolation;
        const int64_t num_points = total;
        if (interp.empty()) {
            // Not authored: infer from the count (USD's default is constant for primvars, vertex for widths).
            // A count that fits only `varying` (segment ends) is read so too: some writers leave it out.
            interp = n == num_points * es    ? "vertex"
                     : n == ev.num_varying * es ? "varying"
                     : n == num_curves * es     ? "uniform"
                     : n == es                  ? "constant"
                     : is_widths                ? "vertex"
                                                : "constant";
        }
        if (interp == "faceVarying") interp = "varying";
        int64_t expected = 0;
        Domain domain = Domain::Point;
        if (interp == "vertex") expected = num_points;
        else if (interp == "varying") expected = ev.num_varying;
        else if (interp == "uniform") expected = num_curves, domain = Domain::Curve;
        else if (interp == "constant") expected = 1, domain = Domain::Detail;
        else fail_at_line(file, pp->line, "unknown interpolation '" + pp->interpolation + "' for " + label);
        if (n != expected * es) {
            fail_at_line(file, pp->line, label + " has " + std::to_string(n) + " values but interpolation '" + interp + "'" +
                                             (es > 1 ? " with elementSize " + std::to_string(es) : std::string()) + " needs " + std::to_string(expected * es));
        }
        if (es > 1) {
            // N values per element: three floats are a float3 column; other shapes have no column type.
            if (es == 3 && std::holds_alternative<std::vector<float>>(data)) {
                const auto& f = std::get<std::vector<float>>(data);
                std::vector<float3> v(static_cast<size_t>(expected));
                for (size_t i = 0; i < v.size(); ++i) v[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
                data = std::move(v);
            }
            else {
                if (warn) {
                    warn(file + ":" + std::to_string(pp->line) + ": " + label + " of <" + cp.path + "> has elementSize " + std::to_string(es) + " (" +
                         std::string(type_name(static_cast<AttrType>(data.index()))) + "), which no attribute type holds; left out");
                }
                continue;
            }
        }
        const AttrType type = static_cast<AttrType>(data.index());
        if (type == AttrType::String && domain != Domain::Detail) continue;  // per-element strings: no column type for them
        if (is_widths) {
            // widths -> point float `width` (diameters) whatever the authored interpolation, scaled like the points.
            AttributeData per_point;
            if (domain == Domain::Point) {
                per_point = through(interp == "vertex" ? ev.vertex : ev.varying, data);
            }
            else {
                const auto& w = std::get<std::vector<float>>(data);
                std::vector<float> v(out.num_points());
                for (int64_t c = 0; c < num_curves; ++c) {
                    const IndexRange r = out.points_of(c);
                    for (int64_t i = r.begin; i < r.end; ++i) v[i] = domain == Domain::Curve ? w[c] : w[0];
                }
                per_point = std::move(v);
            }
            // Catmull-Rom (and NURBS) overshoot: from authored widths all >= 0, a width below zero is
            // that overshoot, not data, and a diameter cannot be negative. Authored negative or
            // non-finite widths are left as they are, for validate() to refuse naming the point.
            const auto& authored = std::get<std::vector<float>>(data);
            const bool clean = std::all_of(authored.begin(), authored.end(), [](float w) { return std::isfinite(w) && w >= 0; });
            for (float& w : std::get<std::vector<float>>(per_point)) {
                if (width_scale != 1.0) w = static_cast<float>(w * width_scale);
                if (clean && w < 0) w = 0;
            }
            if (out.attributes(Domain::Point).find(name)) out.attributes(Domain::Point).remove(name);
            out.attributes(Domain::Point).add(name, Domain::Point, AttrType::Float, 0).data = std::move(per_point);
            continue;
        }
        if (out.attributes(domain).find(name)) continue;  // widths already gave `width`
        if (domain == Domain::Point) data = through(interp == "vertex" ? ev.vertex : ev.varying, data);
        out.attributes(domain).add(name, domain, type, 0).data = std::move(data);
    }
    // The prim's wrap says whether its curves are loops (a primvar of that name does not).
    set_closed(out, cp.type_name != "NurbsCurves" && token("wrap", "nonperiodic") == "periodic" && out.num_curves() > 0);
    out.validate(file);
    return out;
}

/// The layer's `upAxis` and `metersPerUnit` as the curves' detail strings `up_axis` and `units`,
/// which `groom transform` converts from and the writer puts back: a Z-up file (Blender's) had been
/// written out as Y-up without a word, and `transform --up-axis z` turned its hair on its side (a
/// trial). A Y-up layer sets nothing unless the curves said otherwise (files groom writes say Y
/// always, and read back must write the same bytes); a unit groom has no name for is warned of.
void apply_layer_units(const Layer& layer, const std::string& file, CurveSet& curves, const Warn& warn)
{
    if (layer.up_axis == "Z" || (layer.up_axis == "Y" && !curves.detail_string("up_axis").empty())) {
        curves.set_detail_string("up_axis", layer.up_axis);
    }
    else if (!layer.up_axis.empty() && layer.up_axis != "Y" && warn) {
        warn(file + ": upAxis '" + layer.up_axis + "' is neither Y nor Z (USD's two); taken as Y");
    }
    if (layer.meters_per_unit > 0.0) curves.set_detail_string("units", unit_text(layer.meters_per_unit));
}

/// Concatenates the prims' CurveSets in one pass (linear in the total). Point and curve columns present
/// in every part (same type) are kept; a column missing from some part cannot be filled honestly and
/// is dropped with a warning. Detail values come from the first part.
CurveSet concatenate(std::vector<CurveSet>& parts, const std::string& file, const Warn& warn)
{
    if (parts.size() == 1) return std::move(parts[0]);
    std::vector<int64_t> offsets{0};
    for (const CurveSet& p : parts)
        for (size_t c = 1; c <= p.num_curves(); ++c) offsets.push_back(offsets.back() + p.points_in(c - 1));
    CurveSet all;
    all.set_offsets(std::move(offsets));
    for (Domain d : {Domain::Point, Domain::Curve}) {
        for (const Attribute& a : parts[0].attributes(d).all()) {
            bool everywhere = true;
            for (const CurveSet& p : parts) {
                const Attribute* b = p.attributes(d).find(a.name);
                everywhere = everywhere && b && b->type() == a.type();
            }
            if (!everywhere) {
                if (warn) warn(file + ": " + std::string(domain_name(d)) + " attribute '" + a.name + "' is not on every curves prim; left out");
                continue;
            }
            Attribute* dst = all.attributes(d).find(a.name);
            if (!dst) dst = &all.attributes(d).add(a.name, d, a.type(), 0);
            std::visit(
                [&](auto& v) {
                    using V = std::decay_t<decltype(v)>;
                    v.clear();
                    v.reserve(d == Domain::Point ? all.num_points() : all.num_curves());
                    for (const CurveSet& p : parts) {
                        const auto& w = std::get<V>(p.attributes(d).find(a.name)->data);
                        v.insert(v.end(), w.begin(), w.end());
                    }
                },
                dst->data);
        }
    }
    for (const Attribute& a : parts[0].attributes(Domain::Detail).all()) all.attributes(Domain::Detail).all().push_back(a);
    return all;
}

}  // namespace
}  // namespace usda

CurveSet read_usda(const FileBytes& file, const CurveReadOptions& options)
{
    using namespace usda;
    const Layer layer = parse_layer(file);
    const Warn& warn = options.warn;
    std::vector<std::string> skipped;
    const std::vector<ComposedCurves> prims = compose_curves(layer, file.name, options.prims, warn, skipped);
    std::vector<CurveSet> parts;
    std::string paths;  // options.prim_paths: the read prims' paths, one a line
    for (const ComposedCurves& cp : prims) {
        try {
            CurveSet cs = build_prim(file.name, cp, options, warn);
            if (cs.num_curves() == 0) continue;
            if (options.prim_paths) {
                cs.attributes(Domain::Curve).remove("prim");
                auto prim = cs.add<int32_t>(Domain::Curve, "prim");
                std::fill(prim.begin(), prim.end(), int32_t(parts.size()));
                paths += (paths.empty() ? "" : "\n") + cp.path;
            }
            parts.push_back(std::move(cs));
        }
        catch (const Error& e) {
            // ParseError (the prim's data), InvalidGeometry (a transform that overflows the points,
            // non-finite widths): this prim only.
            skipped.push_back(e.what());
            if (warn) warn(std::string(e.what()) + "; prim <" + cp.path + "> skipped");
        }
    }
    if (parts.empty()) {
        if (!skipped.empty()) {
            std::string msg = file.name + ": no curves prim could be read (" + std::to_string(skipped.size()) + " skipped): " + skipped[0];
            for (size_t i = 1; i < std::min<size_t>(skipped.size(), 4); ++i) msg += "; " + skipped[i];
            throw ParseError(msg);
        }
        if (prims.empty()) {
            throw ParseError(file.name + ": expected a 'def BasisCurves' or 'def NurbsCurves' prim" +
                             (options.prims.empty() ? std::string() : " under the prims chosen with --prim") + ", found none");
        }
        return CurveSet();  // only prims with no curves: an empty but valid result
    }
    const bool loops = std::all_of(parts.begin(), parts.end(), [](const CurveSet& part) { return is_closed(part); });
    CurveSet all = concatenate(parts, file.name, warn);
    set_closed(all, loops);  // closed only where every prim read was periodic
    if (options.prim_paths) {
        all.attributes(Domain::Detail).remove("prim_paths");
        all.set_detail_string("prim_paths", paths);
    }
    apply_layer_units(layer, file.name, all, warn);
    all.validate(file.name);
    return all;
}

}  // namespace groom::io
