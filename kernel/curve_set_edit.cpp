#include "kernel/curve_set_edit.h"

#include <algorithm>
#include <string>
#include <type_traits>

namespace groom {

CurveSet join(const CurveSet& a, const CurveSet& b)
{
    std::vector<int64_t> counts;
    counts.reserve(a.num_curves() + b.num_curves());
    for (size_t c = 0; c < a.num_curves(); ++c) counts.push_back(a.points_in(c));
    for (size_t c = 0; c < b.num_curves(); ++c) counts.push_back(b.points_in(c));
    CurveSet dst = CurveSet::from_counts(counts);
    for (Domain d : {Domain::Point, Domain::Curve}) {
        const size_t na = d == Domain::Point ? a.num_points() : a.num_curves();
        // Every column of either side, in a's order then b's new ones.
        std::vector<std::string> names;
        for (const Attribute& col : a.attributes(d).all()) names.push_back(col.name);
        for (const Attribute& col : b.attributes(d).all())
            if (!a.attributes(d).find(col.name)) names.push_back(col.name);
        for (const std::string& name : names) {
            const Attribute* ca = a.attributes(d).find(name);
            const Attribute* cb = b.attributes(d).find(name);
            if (ca && cb && ca->type() != cb->type()) {
                throw InvalidGeometry(std::string("join: ") + domain_name(d) + " attribute '" + name + "' is " +
                                      type_name(ca->type()) + " in the first set but " + type_name(cb->type()) + " in the second");
            }
            const AttrType type = (ca ? ca : cb)->type();
            Attribute& out = dst.attributes(d).add(name, d, type, dst.domain_size(d));
            std::visit(
                [&](auto& values) {
                    using T = typename std::decay_t<decltype(values)>::value_type;
                    T fill{};
                    // -1 marks "none" in integer columns (a guide index, a shape id), where 0 is a value.
                    if constexpr (std::is_integral_v<T>) fill = T(-1);
                    std::fill(values.begin(), values.end(), fill);
                    if (ca) {
                        const auto& src = std::get<std::vector<T>>(ca->data);
                        std::copy(src.begin(), src.end(), values.begin());
                    }
                    if (cb) {
                        const auto& src = std::get<std::vector<T>>(cb->data);
                        std::copy(src.begin(), src.end(), values.begin() + na);
                    }
                },
                out.data);
        }
    }
    for (const CurveSet* s : {&a, &b}) {
        for (const Attribute& col : s->attributes(Domain::Detail).all()) {
            if (!dst.attributes(Domain::Detail).find(col.name)) dst.attributes(Domain::Detail).all().push_back(col);
        }
    }
    set_closed(dst, is_closed(a) && is_closed(b));  // open curves joined to loops are not all loops
    return dst;
}

namespace {

/// Curves of `counts` points gathered from `src`: dst point i is src point src_point[i] (every point
/// column carried), dst curve c is src curve src_curve[c] (every curve and detail column carried).
CurveSet gathered(const CurveSet& src, std::span<const int64_t> counts, std::span<const int64_t> src_point,
                  std::span<const int64_t> src_curve)
{
    CurveSet dst = CurveSet::from_counts(counts);
    const auto P = src.positions();
    const auto Q = dst.positions_for_write();
    for (size_t i = 0; i < src_point.size(); ++i) Q[i] = P[size_t(src_point[i])];
    carry_point_attributes(src, dst, src_point, {attr::P});
    carry_curve_attributes(src, dst, src_curve);
    return dst;
}

/// Whether curve `r` of points `P` ends where it starts (a loop as the readers give it).
bool repeats_first(std::span<const float3> P, const IndexRange& r)
{
    return r.size() >= 3 && P[size_t(r.begin)] == P[size_t(r.end - 1)];
}

}  // namespace

CurveSet remove_curves(const CurveSet& src, std::span<const char> remove, std::vector<int64_t>* kept)
{
    if (remove.size() != src.num_curves()) {
        throw InvalidParam("remove_curves: the mask has " + std::to_string(remove.size()) + " values for " +
                           std::to_string(src.num_curves()) + " curves");
    }
    std::vector<int64_t> src_curve, counts, src_point;
    for (size_t c = 0; c < src.num_curves(); ++c) {
        if (remove[c]) continue;
        src_curve.push_back(int64_t(c));
        counts.push_back(src.points_in(c));
        const IndexRange r = src.points_of(c);
        for (int64_t i = r.begin; i < r.end; ++i) src_point.push_back(i);
    }
    CurveSet dst = gathered(src, counts, src_point, src_curve);
    set_closed(dst, is_closed(src));  // the curves left are the same loops
    if (kept) *kept = std::move(src_curve);
    return dst;
}

namespace {

/// A copy of `src` with each curve's closing point (its first point repeated at its end) present
/// (`closing`) or not, the mark set to match: the one walk behind both public forms below.
CurveSet with_ends(const CurveSet& src, bool closing)
{
    const auto P = src.positions();
    std::vector<int64_t> counts, src_point, src_curve;
    for (size_t c = 0; c < src.num_curves(); ++c) {
        const IndexRange r = src.points_of(c);
        const bool loop = repeats_first(P, r);
        const int64_t kept = r.size() - (!closing && loop ? 1 : 0);
        for (int64_t i = 0; i < kept; ++i) src_point.push_back(r.begin + i);
        const bool add = closing && r.size() >= 2 && !loop;
        if (add) src_point.push_back(r.begin);
        counts.push_back(kept + (add ? 1 : 0));
        src_curve.push_back(int64_t(c));
    }
    CurveSet dst = gathered(src, counts, src_point, src_curve);
    set_closed(dst, closing);
    return dst;
}

}  // namespace

bool all_loops(const CurveSet& curves)
{
    const auto P = curves.positions();
    for (size_t c = 0; c < curves.num_curves(); ++c)
        if (!repeats_first(P, curves.points_of(c))) return false;
    return true;
}

CurveSet without_closing_points(const CurveSet& src) { return with_ends(src, false); }

CurveSet with_closing_points(const CurveSet& src) { return with_ends(src, true); }

}  // namespace groom
