// From parsed BasisCurves prims (usda_syntax.h) to one CurveSet: counts and points checked, cubic curves evaluated
// into polylines, primvars mapped to columns by interpolation, every prim of the file concatenated in file order.
// Kept apart from parsing because it is geometry, not syntax; read_usda, which runs both, is here.
#include "kernel/io/formats.h"
#include "kernel/io/usda_syntax.h"
#include "kernel/math/spline.h"

#include <algorithm>
#include <cmath>

namespace groom::io {

namespace usda {
namespace {

/// Expands an indexed primvar: out[i] = values[indices[i]].
AttributeData expand_indexed(const FileBytes& file, const Primvar& pv)
{
    return std::visit(
        [&](const auto& values) -> AttributeData {
            using V = std::decay_t<decltype(values)>;
            V out;
            out.reserve(pv.indices.size());
            for (int32_t i : pv.indices) {
                if (i < 0 || static_cast<size_t>(i) >= values.size()) {
                    fail_at_line(file.name, pv.line, "primvars:" + pv.name + ":indices holds " + std::to_string(i) + ", out of range (" +
                                                         std::to_string(values.size()) + " values)");
                }
                out.push_back(values[i]);
            }
            return out;
        },
        pv.data);
}

size_t data_size(const AttributeData& d)
{
    return std::visit([](const auto& v) { return v.size(); }, d);
}

/// Per-curve count of `varying` values for a cubic curve of n control points.
int64_t varying_count(int64_t n, bool cubic, bool pinned)
{
    if (!cubic) return n;
    return pinned ? n : std::max<int64_t>(n - 2, 0);
}

/// One BasisCurves prim as a linear CurveSet (cubic curves evaluated into polylines).
CurveSet build_prim(const FileBytes& file, CurvesPrim& cp, const CurveReadOptions& options)
{
    const std::string where = file.name + ":" + std::to_string(cp.line) + ": BasisCurves <" + cp.path + ">";
    if (!cp.points) throw ParseError(where + " has no 'points'");
    if (!cp.counts) throw ParseError(where + " has no 'curveVertexCounts'");
    const std::vector<float3>& pts = *cp.points;
    const std::vector<int32_t>& counts = *cp.counts;
    int64_t total = 0;
    for (size_t c = 0; c < counts.size(); ++c) {
        if (counts[c] < 0) {
            fail_at_line(file.name, cp.counts_line, "curveVertexCounts[" + std::to_string(c) + "] is negative (" + std::to_string(counts[c]) + ")");
        }
        total += counts[c];
    }
    if (total != static_cast<int64_t>(pts.size())) {
        fail_at_line(file.name, cp.counts_line, "curveVertexCounts sum to " + std::to_string(total) + " but 'points' (line " +
                                                    std::to_string(cp.points_line) + ") has " + std::to_string(pts.size()) + " points");
    }
    for (size_t i = 0; i < pts.size(); ++i) {
        if (!isfinite(pts[i])) fail_at_line(file.name, cp.points_line, "points[" + std::to_string(i) + "] is not finite (NaN or inf)");
    }

    bool cubic = false, pinned = false;
    CubicBasis basis = CubicBasis::CatmullRom;
    if (cp.type == "cubic") {
        cubic = true;
        if (cp.basis == "catmullRom") basis = CubicBasis::CatmullRom;
        else if (cp.basis == "bspline") basis = CubicBasis::BSpline;
        else throw ParseError(where + ": cubic basis '" + cp.basis + "' is not supported (expected catmullRom or bspline; "
                              "write 'uniform token basis' explicitly: the USD default is bezier)");
        if (cp.wrap == "pinned") pinned = true;
        else if (cp.wrap != "nonperiodic") throw ParseError(where + ": wrap '" + cp.wrap + "' is not supported for cubic curves (expected nonperiodic or pinned)");
        for (size_t c = 0; c < counts.size(); ++c) {
            const int need = pinned ? 2 : 4;
            if (counts[c] < need) {
                fail_at_line(file.name, cp.counts_line, "cubic " + cp.wrap + " curve " + std::to_string(c) + " has " + std::to_string(counts[c]) +
                                                            " points; it needs at least " + std::to_string(need));
            }
        }
    }
    else if (cp.type == "linear") {
        if (cp.wrap == "periodic") throw ParseError(where + ": wrap 'periodic' (closed curves) is not supported; expected nonperiodic");
    }
    else {
        throw ParseError(where + ": curve type '" + cp.type + "' is not supported (expected linear or cubic)");
    }

    // Control-point topology first; cubic curves are evaluated at the end.
    CurveSet cvs = CurveSet::from_counts(std::span<const int32_t>(counts));
    std::copy(pts.begin(), pts.end(), cvs.positions_for_write().begin());
    const int64_t num_curves = static_cast<int64_t>(counts.size()), num_points = total;
    int64_t num_varying = 0;
    for (int32_t n : counts) num_varying += varying_count(n, cubic, pinned);

    // Varying primvars of cubic curves live on segment ends; kept aside and interpolated below.
    std::vector<Primvar*> varying;
    for (Primvar& pv : cp.primvars) {
        AttributeData data = pv.indices.empty() ? std::move(pv.data) : expand_indexed(file, pv);
        const int64_t n = static_cast<int64_t>(data_size(data));
        std::string interp = pv.interpolation;
        if (interp.empty()) {
            // Not authored: infer from the count (USD's default is constant for primvars, vertex for widths).
            interp = n == num_points ? "vertex" : n == num_curves ? "uniform" : n == 1 ? "constant" : pv.name == "widths" ? "vertex" : "constant";
        }
        if (interp == "faceVarying") interp = "varying";
        if (interp == "varying" && !cubic) interp = "vertex";
        int64_t expected = 0;
        Domain domain = Domain::Point;
        if (interp == "vertex") expected = num_points, domain = Domain::Point;
        else if (interp == "varying") expected = num_varying, domain = Domain::Point;
        else if (interp == "uniform") expected = num_curves, domain = Domain::Curve;
        else if (interp == "constant") expected = 1, domain = Domain::Detail;
        else fail_at_line(file.name, pv.line, "unknown interpolation '" + pv.interpolation + "' for " + pv.name);
        const AttrType type = static_cast<AttrType>(data.index());
        if (type == AttrType::String && domain != Domain::Detail) continue;  // per-element strings: no column type for them
        if (n != expected) {
            if (domain == Domain::Detail) continue;  // an array-valued constant (elementSize > 1): not representable, skipped
            fail_at_line(file.name, pv.line, (pv.name == "widths" ? std::string("widths") : "primvars:" + pv.name) + " has " +
                                                 std::to_string(n) + " values but interpolation '" + interp + "' needs " +
                                                 std::to_string(expected));
        }
        pv.data = std::move(data);
        pv.interpolation = interp;
        if (pv.name == "widths") {
            // widths -> point float `width` (diameters), whatever the authored interpolation.
            const auto& w = std::get<std::vector<float>>(pv.data);
            if (interp == "varying") {
                varying.push_back(&pv);
                continue;
            }
            auto dst = cvs.add<float>(Domain::Point, attr::width);
            for (int64_t c = 0; c < num_curves; ++c) {
                const IndexRange r = cvs.points_of(c);
                for (int64_t i = r.begin; i < r.end; ++i) dst[i] = domain == Domain::Point ? w[i] : domain == Domain::Curve ? w[c] : w[0];
            }
            continue;
        }
        if (interp == "varying") {
            varying.push_back(&pv);
            continue;
        }
        if (cvs.attributes(domain).find(pv.name)) continue;  // a second primvar of the same name (widths vs primvars:width)
        Attribute& a = cvs.attributes(domain).add(pv.name, domain, type, 0);
        a.data = std::move(pv.data);
    }
    if (!cubic) {
        cvs.validate(file.name);
        return cvs;
    }

    // Evaluate cubic curves (and their vertex / varying primvars) into polylines.
    const int k = std::max(options.cubic_samples_per_segment, 1);
    std::vector<int64_t> out_counts(counts.size());
    for (size_t c = 0; c < counts.size(); ++c) out_counts[c] = (pinned ? counts[c] - 1 : counts[c] - 3) * int64_t(k) + 1;
    CurveSet out = CurveSet::from_counts(out_counts);
    for (const Attribute& a : cvs.attributes(Domain::Curve).all()) out.attributes(Domain::Curve).all().push_back(a);
    for (const Attribute& a : cvs.attributes(Domain::Detail).all()) out.attributes(Domain::Detail).all().push_back(a);
    auto eval3 = [&](std::span<const float3> src, std::span<float3> dst) {
        for (size_t c = 0; c < counts.size(); ++c) {
            const IndexRange r = cvs.points_of(c);
            const std::vector<float3> e = evaluate_cubic(src.subspan(r.begin, r.size()), basis, pinned, k);
            std::copy(e.begin(), e.end(), dst.begin() + out.points_of(c).begin);
        }
    };
    // Sample j of a curve lies in segment j / k at parameter (j % k) / k; the last sample ends the last segment.
    auto segment_of = [&](int64_t j, int64_t segments, int64_t& s, float& t) {
        s = std::min<int64_t>(j / k, segments - 1);
        t = static_cast<float>(j - s * k) / k;
    };
    for (const Attribute& a : cvs.attributes(Domain::Point).all()) {
        Attribute& dst = out.attributes(Domain::Point).add(a.name, Domain::Point, a.type(), out.num_points());
        if (a.type() == AttrType::Float3) {
            eval3(a.values<float3>(), dst.values<float3>());
        }
        else if (a.type() == AttrType::Float) {
            std::vector<float3> packed(a.size()), result(out.num_points());
            auto src = a.values<float>();
            for (size_t i = 0; i < packed.size(); ++i) packed[i] = {src[i], 0.0f, 0.0f};
            eval3(packed, result);
            auto d = dst.values<float>();
            for (size_t i = 0; i < result.size(); ++i) d[i] = result[i].x;
        }
        else {
            // Integers cannot be blended: each sample takes its nearest control point.
            std::visit(
                [&](const auto& src) {
                    using V = std::decay_t<decltype(src)>;
                    if constexpr (!std::is_same_v<V, std::vector<float>> && !std::is_same_v<V, std::vector<float3>>) {
                        auto& d = std::get<V>(dst.data);
                        for (size_t c = 0; c < counts.size(); ++c) {
                            const int64_t segs = pinned ? counts[c] - 1 : counts[c] - 3;
                            const int64_t first_cv = cvs.points_of(c).begin + (pinned ? 0 : 1);
                            const IndexRange r = out.points_of(c);
                            for (int64_t j = 0; j < r.size(); ++j) {
                                int64_t s;
                                float t;
                                segment_of(j, segs, s, t);
                                d[r.begin + j] = src[first_cv + s + (t >= 0.5f ? 1 : 0)];
                            }
                        }
                    }
                },
                a.data);
        }
    }
    for (Primvar* pv : varying) {
        // Varying values sit on segment ends and blend linearly along each segment.
        const std::string name = pv->name == "widths" ? std::string(attr::width) : pv->name;
        const AttrType type = static_cast<AttrType>(pv->data.index());
        Attribute& dst = out.attributes(Domain::Point).add(name, Domain::Point, type, out.num_points());
        int64_t base = 0;
        for (size_t c = 0; c < counts.size(); ++c) {
            const int64_t segs = pinned ? counts[c] - 1 : counts[c] - 3;
            const IndexRange r = out.points_of(c);
            for (int64_t j = 0; j < r.size(); ++j) {
                int64_t s;
                float t;
                segment_of(j, segs, s, t);
                std::visit(
                    [&](const auto& src) {
                        using V = std::decay_t<decltype(src)>;
                        auto& d = std::get<V>(dst.data);
                        if constexpr (std::is_same_v<V, std::vector<float>>) d[r.begin + j] = src[base + s] + (src[base + s + 1] - src[base + s]) * t;
                        else if constexpr (std::is_same_v<V, std::vector<float3>>) d[r.begin + j] = lerp(src[base + s], src[base + s + 1], t);
                        else d[r.begin + j] = src[base + s + (t >= 0.5f ? 1 : 0)];
                    },
                    pv->data);
            }
            base += varying_count(counts[c], true, pinned);
        }
    }
    eval3(cvs.positions_for_write(), out.positions_for_write());
    out.validate(file.name);
    return out;
}

/// Appends `src` after `dst`. Point and curve columns present in both (same type) are kept; a column
/// missing from either side cannot be filled honestly and is dropped. Detail values come from `dst`.
void append_curves(CurveSet& dst, const CurveSet& src)
{
    if (dst.num_curves() == 0 && dst.attributes(Domain::Point).count() == 1 && dst.attributes(Domain::Detail).count() == 0) {
        dst = src;
        return;
    }
    const size_t old_points = dst.num_points(), old_curves = dst.num_curves();
    std::vector<int64_t> offsets(dst.offsets().begin(), dst.offsets().end());
    for (size_t c = 1; c <= src.num_curves(); ++c) offsets.push_back(static_cast<int64_t>(old_points) + src.offsets()[c]);
    for (Domain d : {Domain::Point, Domain::Curve}) {
        std::vector<std::string> drop;
        for (Attribute& a : dst.attributes(d).all()) {
            const Attribute* b = src.attributes(d).find(a.name);
            if (!b || b->type() != a.type()) {
                drop.push_back(a.name);
                continue;
            }
            std::visit(
                [&](auto& v) {
                    const auto& w = std::get<std::decay_t<decltype(v)>>(b->data);
                    v.resize(d == Domain::Point ? old_points : old_curves);
                    v.insert(v.end(), w.begin(), w.end());
                },
                a.data);
        }
        for (const std::string& n : drop) dst.attributes(d).remove(n);
    }
    dst.set_offsets(std::move(offsets));
}

}  // namespace
}  // namespace usda

CurveSet read_usda(const FileBytes& file, const CurveReadOptions& options)
{
    using namespace usda;
    std::vector<CurvesPrim> prims = parse_curves_prims(file);
    if (prims.empty()) throw ParseError(file.name + ": expected a 'def BasisCurves' prim, found none");
    CurveSet all;
    for (CurvesPrim& cp : prims) append_curves(all, build_prim(file, cp, options));
    all.validate(file.name);
    return all;
}

}  // namespace groom::io
