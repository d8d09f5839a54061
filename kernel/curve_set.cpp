#include "kernel/curve_set.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <cmath>
#include <string>

namespace groom {

CurveSet::CurveSet() : offsets_{0}
{
    attributes(Domain::Point).add(attr::P, Domain::Point, AttrType::Float3, 0);
}

CurveSet CurveSet::from_counts(std::span<const int64_t> counts)
{
    CurveSet cs;
    cs.set_counts(counts);
    return cs;
}

CurveSet CurveSet::from_counts(std::span<const int32_t> counts)
{
    std::vector<int64_t> wide(counts.begin(), counts.end());
    return from_counts(std::span<const int64_t>(wide));
}

size_t CurveSet::domain_size(Domain d) const
{
    switch (d) {
        case Domain::Point: return num_points();
        case Domain::Curve: return num_curves();
        case Domain::Detail: return 1;
    }
    return 0;
}

void CurveSet::set_counts(std::span<const int64_t> counts)
{
    std::vector<int64_t> offsets(counts.size() + 1, 0);
    for (size_t c = 0; c < counts.size(); ++c) {
        if (counts[c] < 0) {
            throw InvalidGeometry("curve " + std::to_string(c) + " has a negative point count (" + std::to_string(counts[c]) + ")");
        }
        offsets[c + 1] = offsets[c] + counts[c];
    }
    set_offsets(std::move(offsets));
}

void CurveSet::set_offsets(std::vector<int64_t> offsets)
{
    if (offsets.empty() || offsets.front() != 0) throw InvalidGeometry("curve offsets must start at 0");
    for (size_t i = 1; i < offsets.size(); ++i) {
        if (offsets[i] < offsets[i - 1]) {
            throw InvalidGeometry("curve offsets decrease at curve " + std::to_string(i - 1) + " (" +
                                  std::to_string(offsets[i - 1]) + " then " + std::to_string(offsets[i]) + ")");
        }
    }
    offsets_ = std::move(offsets);
    attributes(Domain::Point).resize(num_points());
    attributes(Domain::Curve).resize(num_curves());
    attributes(Domain::Detail).resize(1);
}

std::vector<int64_t> CurveSet::curve_ids() const { return curve_ids(0, num_curves()); }

std::vector<int64_t> CurveSet::curve_ids(size_t begin, size_t end) const
{
    std::vector<int64_t> ids(end - begin);
    if (auto id64 = find<int64_t>(Domain::Curve, attr::id); !id64.empty()) {
        std::copy(id64.begin() + ptrdiff_t(begin), id64.begin() + ptrdiff_t(end), ids.begin());
    }
    else if (auto id32 = find<int32_t>(Domain::Curve, attr::id); !id32.empty()) {
        std::copy(id32.begin() + ptrdiff_t(begin), id32.begin() + ptrdiff_t(end), ids.begin());
    }
    else {
        for (size_t c = 0; c < ids.size(); ++c) ids[c] = static_cast<int64_t>(begin + c);
    }
    return ids;
}

std::string CurveSet::detail_string(std::string_view name, std::string_view fallback) const
{
    auto v = find<std::string>(Domain::Detail, name);
    return v.empty() ? std::string(fallback) : v[0];
}

void CurveSet::set_detail_string(std::string_view name, std::string_view value)
{
    add<std::string>(Domain::Detail, name)[0] = std::string(value);
}

bool is_closed(const CurveSet& curves)
{
    const auto v = curves.find<int32_t>(Domain::Detail, attr::closed);
    return !v.empty() && v[0] == 1;
}

void set_closed(CurveSet& curves, bool closed)
{
    curves.attributes(Domain::Detail).remove(attr::closed);
    if (closed) curves.add<int32_t>(Domain::Detail, attr::closed)[0] = 1;
}

void CurveSet::validate(std::string_view what) const
{
    const std::string where = what.empty() ? std::string() : std::string(what) + ": ";
    if (offsets_.empty() || offsets_.front() != 0) throw InvalidGeometry(where + "curve offsets must start at 0");
    for (size_t i = 1; i < offsets_.size(); ++i) {
        if (offsets_[i] < offsets_[i - 1]) {
            throw InvalidGeometry(where + "curve offsets decrease at curve " + std::to_string(i - 1));
        }
    }
    for (int d = 0; d < 3; ++d) {
        const Domain dom = static_cast<Domain>(d);
        for (const Attribute& a : attributes(dom).all()) {
            if (a.size() != domain_size(dom)) {
                throw InvalidGeometry(where + domain_name(dom) + " attribute '" + a.name + "' has " + std::to_string(a.size()) +
                                      " values (expected " + std::to_string(domain_size(dom)) + ")");
            }
        }
    }
    const Attribute* p = attributes(Domain::Point).find(attr::P);
    if (!p || p->type() != AttrType::Float3) throw InvalidGeometry(where + "point attribute 'P' (float3) is missing");
    auto pos = p->values<float3>();
    // A branch-free pass finds whether any coordinate is not finite (it vectorises: the per-point
    // test below was 4% of `groom curl` on 3.2 M points, perf); only a file that fails is searched
    // for the point to name.
    // The test is on the bits (exponent all ones: inf or NaN), OR-ed into an integer: the compiler
    // vectorises that, where `bool &= fabs(x) <= max` stayed scalar (8 ms a check on 3.2 M points,
    // 6% of `groom curl`, perf; 1.3 ms now).
    static_assert(sizeof(float3) == 3 * sizeof(float));
    const float* xyz = reinterpret_cast<const float*>(pos.data());
    uint32_t not_finite = 0;
    for (size_t i = 0; i < pos.size() * 3; ++i) {
        uint32_t u;
        std::memcpy(&u, xyz + i, sizeof u);
        not_finite |= uint32_t((u & 0x7f800000u) == 0x7f800000u);
    }
    const bool all_finite = not_finite == 0;
    for (size_t i = 0; !all_finite && i < pos.size(); ++i) {
        if (!isfinite(pos[i])) {
            const auto c = std::upper_bound(offsets_.begin(), offsets_.end(), static_cast<int64_t>(i)) - offsets_.begin() - 1;
            throw InvalidGeometry(where + "point " + std::to_string(i) + " (curve " + std::to_string(c) +
                                  ") has a non-finite position (" + std::to_string(pos[i].x) + ", " + std::to_string(pos[i].y) +
                                  ", " + std::to_string(pos[i].z) + ")");
        }
    }
    // A width is a diameter: NaN, inf or a negative one would be carried into every op's output and
    // every renderer; refused where it enters, naming the point.
    for (const Domain dom : {Domain::Point, Domain::Curve}) {
        const Attribute* w = attributes(dom).find(attr::width);
        if (!w || w->type() != AttrType::Float) continue;
        const auto v = w->values<float>();
        // Finite and >= 0 on the bits, vectorised as above: below the exponent's all-ones with the
        // sign clear, or -0 (which compares equal to 0); only a column that fails is searched.
        uint32_t bad = 0;
        for (const float f : v) {
            uint32_t u;
            std::memcpy(&u, &f, sizeof u);
            bad |= uint32_t(u >= 0x7f800000u && u != 0x80000000u);
        }
        for (size_t i = 0; bad && i < v.size(); ++i) {
            if (std::isfinite(v[i]) && v[i] >= 0.0f) continue;
            std::string element = std::string(domain_name(dom)) + " " + std::to_string(i);
            if (dom == Domain::Point) {
                const auto c = std::upper_bound(offsets_.begin(), offsets_.end(), static_cast<int64_t>(i)) - offsets_.begin() - 1;
                element += " (curve " + std::to_string(c) + ")";
            }
            throw InvalidGeometry(where + element + " has width " + format_number(v[i]) + "; expected a finite width >= 0");
        }
    }
}

Bounds3 CurveSet::bounds() const
{
    Bounds3 b;
    for (const float3& p : positions()) b.extend(p);
    return b;
}

void carry_curve_attributes(const CurveSet& src, CurveSet& dst, std::span<const int64_t> src_curve)
{
    for (const Attribute& a : src.attributes(Domain::Curve).all()) {
        if (dst.attributes(Domain::Curve).find(a.name)) continue;
        Attribute& out = dst.attributes(Domain::Curve).add(a.name, Domain::Curve, a.type(), dst.num_curves());
        std::visit(
            [&](const auto& in) {
                auto& o = std::get<std::decay_t<decltype(in)>>(out.data);
                for (size_t c = 0; c < o.size(); ++c) o[c] = in[src_curve[c]];
            },
            a.data);
    }
    for (const Attribute& a : src.attributes(Domain::Detail).all()) {
        // Curves made from loops are not loops themselves (a braid on a closed guide); an op that
        // keeps each curve's ends (resample, select) says so itself.
        if (a.name == attr::closed || dst.attributes(Domain::Detail).find(a.name)) continue;
        dst.attributes(Domain::Detail).all().push_back(a);
    }
}

void carry_point_attributes(const CurveSet& src, CurveSet& dst, std::span<const int64_t> src_point,
                            std::initializer_list<std::string_view> skip)
{
    for (const Attribute& a : src.attributes(Domain::Point).all()) {
        if (std::find(skip.begin(), skip.end(), a.name) != skip.end()) continue;
        if (dst.attributes(Domain::Point).find(a.name)) continue;
        Attribute& out = dst.attributes(Domain::Point).add(a.name, Domain::Point, a.type(), dst.num_points());
        std::visit(
            [&](const auto& in) {
                auto& o = std::get<std::decay_t<decltype(in)>>(out.data);
                for (size_t p = 0; p < o.size(); ++p) o[p] = in[src_point[p]];
            },
            a.data);
    }
}

}  // namespace groom
