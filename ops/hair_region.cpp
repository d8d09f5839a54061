#include "ops/hair_region.h"

#include "kernel/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace groom {

namespace {

constexpr float kPi = 3.14159265358979f;

/// Closest point of segment a-b to p, as the parameter in [0, 1].
float segment_param(const float3& p, const float3& a, const float3& b)
{
    const float3 ab = b - a;
    const float l2 = dot(ab, ab);
    return l2 > 0.0f ? std::clamp(dot(p - a, ab) / l2, 0.0f, 1.0f) : 0.0f;
}

}  // namespace

void HairRegionParams::validate() const
{
    if (!isfinite(up) || length(up) == 0.0f) throw InvalidParam("hair region: `up` must be a finite non-zero direction");
    if (!(parting_gap >= 0.0f) || !std::isfinite(parting_gap)) {
        throw InvalidParam("hair region: `parting_gap` must be a finite number >= 0 (got " + format_number(parting_gap) + ")");
    }
}

std::span<const float3> check_hairline(const CurveSet& hairline, const std::string& who)
{
    if (hairline.num_curves() != 1) {
        throw InvalidGeometry(who + " must be one closed curve around the head; found " + std::to_string(hairline.num_curves()) + " curves");
    }
    auto pts = hairline.positions();
    for (const float3& p : pts)
        if (!isfinite(p)) throw InvalidGeometry(who + " has a point that is not finite");
    double length = 0.0;
    for (size_t i = 1; i < pts.size(); ++i) length += double(distance(pts[i - 1], pts[i]));
    // A closed curve written closed: its first point again at the end (a USD periodic curve as
    // read, an OBJ record ending at its first vertex, a loop of edges from Blender). The same
    // hairline as without that point, which every reader of it takes as a step of azimuth 0 ("point
    // 180 turns back"): dropped. Within float rounding of the first, not merely near it: a last point
    // a little past the first is an overlap, and stays one.
    if (pts.size() > 1 && double(distance(pts.front(), pts.back())) <= 1e-6 * length) {
        length -= double(distance(pts[pts.size() - 2], pts.back()));
        pts = pts.first(pts.size() - 1);
    }
    if (pts.size() < 8) throw InvalidGeometry(who + " must have at least 8 points; found " + std::to_string(pts.size()));
    const double gap = double(distance(pts.front(), pts.back()));
    if (gap > 0.1 * length) {
        throw InvalidGeometry(who + " must be one closed curve around the head, but its ends are " + format_number(gap) + " apart on a curve " +
                              format_number(length) + " long (an open curve: a parting line?); `groom hairline` makes one");
    }
    return pts;
}

HairRegion::HairRegion(const Surface& scalp, const CurveSet& hairline, const CurveSet& partings, const HairRegionParams& params)
    : params_(params)
{
    params_.validate();
    params_.up = normalize(params_.up);
    e1_ = any_perpendicular(params_.up);
    e2_ = cross(params_.up, e1_);

    if (hairline.num_curves() > 0) {
        const auto pts = check_hairline(hairline, "hairline");
        hairline_.assign(pts.begin(), pts.end());
        centroid_ = std::accumulate(pts.begin(), pts.end(), float3{}) * (1.0f / float(pts.size()));
        // Azimuths must turn one way once around the axis: the hairline is then a height function
        // of the azimuth, and inside/outside is a comparison of elevations.
        std::vector<float> all_az(pts.size()), all_el(pts.size());
        for (size_t i = 0; i < pts.size(); ++i) azimuth_elevation(pts[i], all_az[i], all_el[i]);
        const auto step = [](double from, double to) {
            double d = to - from;
            if (d > kPi) d -= 2 * kPi;
            if (d < -kPi) d += 2 * kPi;
            return d;
        };
        // The way it turns, from all its steps; a point that steps back against it by no more than
        // a fifth of a degree (a vertex repeated, a scan's wobble: `edges` took such hairlines and
        // this refused them, a hostile trial) is left out, a larger step back refused.
        double total = 0.0;
        for (size_t i = 0; i < pts.size(); ++i) total += step(all_az[i], all_az[(i + 1) % pts.size()]);
        const int sign = total >= 0.0 ? 1 : -1;
        constexpr double kWobble = 0.2 * kPi / 180.0;
        std::vector<float> az, el;
        for (size_t i = 0; i < pts.size(); ++i) {
            if (!az.empty()) {
                const double d = step(az.back(), all_az[i]) * sign;
                if (!(d > 0.0)) {
                    if (d >= -kWobble) continue;
                    throw InvalidGeometry("hairline: it must go once around the head (around the `up` axis through its centroid) without "
                                          "turning back; point " + std::to_string(i) + " turns back");
                }
            }
            az.push_back(all_az[i]);
            el.push_back(all_el[i]);
        }
        while (az.size() > 1 && !(step(az.back(), az.front()) * sign > 0.0)) {
            if (step(az.back(), az.front()) * sign < -kWobble) {
                throw InvalidGeometry("hairline: it must go once around the head (around the `up` axis through its centroid) without "
                                      "turning back; point " + std::to_string(pts.size() - 1) + " turns back");
            }
            az.pop_back();
            el.pop_back();
        }
        double turn = 0.0;
        for (size_t i = 0; i < az.size(); ++i) turn += step(az[i], az[(i + 1) % az.size()]);
        if (std::fabs(std::fabs(turn) - 2 * kPi) > 0.1) {
            throw InvalidGeometry("hairline: it must go once around the head; it turns " + format_number(turn * 180 / kPi) + " degrees");
        }
        std::vector<size_t> order(az.size());
        std::iota(order.begin(), order.end(), size_t(0));
        std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return az[a] < az[b]; });
        for (size_t i : order) {
            azimuth_.push_back(az[i]);
            elevation_.push_back(el[i]);
        }
    }
    (void)scalp;

    if (partings.num_curves() > 64) throw InvalidGeometry("parting: at most 64 partings, found " + std::to_string(partings.num_curves()));
    const auto pts = partings.positions();
    for (size_t c = 0; c < partings.num_curves(); ++c) {
        const IndexRange r = partings.points_of(c);
        if (r.size() < 2) throw InvalidGeometry("parting: curve " + std::to_string(c) + " has " + std::to_string(r.size()) + " points; expected >= 2");
        Parting part;
        part.points.assign(pts.begin() + r.begin, pts.begin() + r.end);
        for (size_t i = 0; i + 1 < part.points.size(); ++i) {
            const float3 mid = (part.points[i] + part.points[i + 1]) * 0.5f;
            const float3 n = scalp.normal(mid);
            const float3 t = normalize(part.points[i + 1] - part.points[i]);
            part.side.push_back(normalize(cross(t, n)));
        }
        partings_.push_back(std::move(part));
    }
}

void HairRegion::azimuth_elevation(const float3& p, float& azimuth, float& elevation) const
{
    const float3 v = p - centroid_;
    const float h = dot(v, params_.up);
    const float x = dot(v, e1_), y = dot(v, e2_);
    azimuth = std::atan2(y, x);
    elevation = std::atan2(h, std::hypot(x, y));
}

float HairRegion::hairline_margin(const float3& p) const
{
    if (elevation_.empty()) return kPi;
    float az, el;
    azimuth_elevation(p, az, el);
    // The hairline's elevation at az: linear between the two samples around it (periodic).
    const size_t n = azimuth_.size();
    const size_t hi = std::upper_bound(azimuth_.begin(), azimuth_.end(), az) - azimuth_.begin();
    const size_t i1 = hi % n, i0 = (hi + n - 1) % n;
    float a0 = azimuth_[i0], a1 = azimuth_[i1];
    if (hi == 0) a0 -= 2 * kPi;
    if (hi == n) a1 += 2 * kPi;
    const float t = a1 > a0 ? (az - a0) / (a1 - a0) : 0.0f;
    const float line = elevation_[i0] + (elevation_[i1] - elevation_[i0]) * t;
    return el - line;
}

bool HairRegion::inside_hairline(const float3& p) const { return hairline_margin(p) > 0.0f; }

int HairRegion::side_of(const Parting& part, const float3& p, float* dist) const
{
    float best = std::numeric_limits<float>::infinity();
    size_t seg = 0;
    for (size_t i = 0; i + 1 < part.points.size(); ++i) {
        const float t = segment_param(p, part.points[i], part.points[i + 1]);
        const float d = distance(p, part.points[i] + (part.points[i + 1] - part.points[i]) * t);
        if (d < best) {
            best = d;
            seg = i;
        }
    }
    if (dist) *dist = best;
    const float3 q = part.points[seg] + (part.points[seg + 1] - part.points[seg]) * segment_param(p, part.points[seg], part.points[seg + 1]);
    return dot(p - q, part.side[seg]) >= 0.0f ? 1 : 0;
}

float HairRegion::parting_distance(const float3& p) const
{
    float best = std::numeric_limits<float>::infinity();
    for (const Parting& part : partings_) {
        float d;
        side_of(part, p, &d);
        best = std::min(best, d);
    }
    return best;
}

uint64_t HairRegion::section(const float3& p) const
{
    uint64_t mask = 0;
    for (size_t i = 0; i < partings_.size(); ++i)
        if (side_of(partings_[i], p, nullptr)) mask |= uint64_t(1) << i;
    return mask;
}

bool HairRegion::haired(const float3& p) const
{
    return inside_hairline(p) && parting_distance(p) > 0.5f * params_.parting_gap;
}

bool HairRegion::crosses_parting(const float3& a, const float3& b) const
{
    for (const Parting& part : partings_) {
        float da, db;
        const int sa = side_of(part, a, &da), sb = side_of(part, b, &db);
        if (sa != sb && std::min(da, db) <= distance(a, b)) return true;
    }
    return false;
}

}  // namespace groom
