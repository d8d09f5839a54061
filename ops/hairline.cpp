#include "ops/hairline.h"

#include "kernel/error.h"

#include <array>
#include <cmath>
#include <limits>
#include <vector>
#include <string>

namespace groom {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Height below the top (fraction of the head length) at azimuth `deg` in [0, 180], mirrored for the
/// other side: a cubic Hermite through key heights with Catmull-Rom slopes, flattened at every key
/// that is a local extreme so the curve never overshoots (a hairline dipping past the sideburn).
double drop_at(const HairlineParams& p, double deg)
{
    deg = std::fabs(deg);
    const double f = p.forehead, t = p.temple, s = p.sideburn, e = p.ear, n = p.nape;
    // Keys from the forehead round to the nape; the mirror images at -30 and 210 give end slopes 0.
    const std::array<double, 11> x{-30, 0, 30, 55, 80, 92, 105, 130, 155, 180, 210};
    const std::array<double, 11> y{f + 0.2 * (t - f), f, f + 0.2 * (t - f), t, s, e + 0.04, e, e + 0.55 * (n - e), n - 0.02, n, n - 0.02};
    size_t i = 1;
    while (i + 2 < x.size() && deg > x[i + 1]) ++i;
    auto slope = [&](size_t k) {
        if ((y[k] - y[k - 1]) * (y[k + 1] - y[k]) <= 0.0) return 0.0;
        return (y[k + 1] - y[k - 1]) / (x[k + 1] - x[k - 1]);
    };
    const double h = x[i + 1] - x[i], u = (deg - x[i]) / h;
    const double m0 = slope(i) * h, m1 = slope(i + 1) * h;
    const double u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * y[i] + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * y[i + 1] + (u3 - u2) * m1;
}

/// Where the ray from `outside` toward `axis` first enters the scalp (the outermost surface).
bool outermost_hit(const Surface& scalp, const float3& outside, const float3& axis, float3& hit)
{
    return scalp.first_intersection(outside, axis, hit);
}

/// The top of an ear above the hairline at this azimuth: the drop (below the top of the head) of the
/// last skull hit above a jump, or -1 when the horizontal rays from 0.3 head lengths below the top
/// (above any ear) down to `drop` meet no ear. Scanning down in steps of 1% of the length, the hit
/// moves out slowly on the side of a skull (under 1% a step there: a sphere's side at that depth moves
/// 0.6%) and jumps out at the top of an ear, a rim standing a centimetre or two off the head: a jump
/// of over 2%.
double ear_top_above(const Surface& scalp, const float3& top, const float3& up, const float3& d, float reach, double length, double drop)
{
    const double step = 0.01 * length, jump = 0.02 * length;
    double prev = 0.0;
    bool have_prev = false;
    for (int k = 0; 0.3 * length + k * step < drop; ++k) {
        const double h = 0.3 * length + k * step;
        const float3 a = top - up * float(h);
        float3 hit;
        if (!outermost_hit(scalp, a + d * reach, a, hit)) {
            have_prev = false;
            continue;
        }
        const double r = double(dot(hit - a, d));
        if (have_prev && r - prev > jump) return h - step;
        prev = r;
        have_prev = true;
    }
    return -1.0;
}

}  // namespace

std::string HairlineReport::warning(const std::string& command, const float3& forward) const
{
    return command + ": warning: the head seems to face away from --forward " + format_xyz(forward) + ": 0.8-0.9 head lengths below its top the scalp reaches " +
           format_number(back) + " behind the head's middle and " + format_number(front) +
           " in front (a face and chin in front, a neck behind, expected), so the hairline's nape may cross the face; if the face looks the "
           "other way pass --forward " + format_xyz(float3(0.0f, 0.0f, 0.0f) - forward);
}

std::string HairlineReport::axis_message(const std::string& command) const
{
    const std::string off = format_number(length(middle_offset));
    if (moved_axis) {
        return command + ": the middle of the scalp's bounds is " + off + " off the head's middle (a bust's or a body's is not its head's), " +
               "so the head's axis runs through its middle, about " + format_xyz(suggested_center) + ", instead; pass --center to choose another";
    }
    return command + ": warning: --center is " + off + " off the head's middle 0.36 head lengths below its top, over 0.15 of the length: " +
           "the hairline's rays start from there and may cross the face or the ears; the head's middle is about " + format_xyz(suggested_center);
}

std::vector<std::pair<bool, std::string>> HairlineReport::messages(const std::string& command, const float3& forward) const
{
    std::vector<std::pair<bool, std::string>> out;
    if (axis_off_middle) out.emplace_back(!moved_axis, axis_message(command));
    if (faces_backward()) out.emplace_back(true, warning(command, forward));
    return out;
}

void HairlineParams::validate() const
{
    if (!isfinite(up) || length(up) == 0.0f) throw InvalidParam("hairline: `up` must be a finite non-zero direction");
    if (!isfinite(forward) || length(cross(up, forward)) < 1e-3f * length(up) * length(forward)) {
        throw InvalidParam("hairline: `forward` must be a finite direction not parallel to `up`");
    }
    if (has_center && !isfinite(center)) throw InvalidParam("hairline: `center` must be finite");
    if (!(head_length >= 0.0f) || !std::isfinite(head_length)) {
        throw InvalidParam("hairline: `head_length` must be a finite number >= 0 (got " + format_number(head_length) + ")");
    }
    const std::pair<const char*, float> fractions[] = {
        {"forehead", forehead}, {"temple", temple}, {"sideburn", sideburn}, {"ear", ear}, {"nape", nape}};
    for (auto [name, v] : fractions) {
        if (!(v > 0.0f && v < 2.0f)) {
            throw InvalidParam("hairline: `" + std::string(name) + "` must be in (0, 2) head lengths below the top (got " + format_number(v) + ")");
        }
    }
    if (points < 16 || points > 100000) throw InvalidParam("hairline: `points` must be in [16, 100000] (got " + std::to_string(points) + ")");
}

CurveSet make_hairline(const Surface& scalp, const Bounds3& bounds, const HairlineParams& params, HairlineReport* report)
{
    params.validate();
    if (bounds.empty()) throw InvalidGeometry("hairline: the scalp is empty");
    const float3 up = normalize(params.up);
    const float3 fwd = normalize(params.forward - up * dot(params.forward, up));
    const float3 side = cross(up, fwd);
    const float reach = length(bounds.size()) + 1.0f;

    // The head's axis: a vertical line through the centre; its top is the highest scalp point on it.
    float3 c = params.has_center ? params.center : bounds.center();
    float3 top;
    float length_fb = params.head_length;
    const auto find_top_and_length = [&] {
        if (!outermost_hit(scalp, c + up * reach, c, top)) {
            throw InvalidGeometry("hairline: no scalp above the centre " + format_xyz(c) + " (give --center inside the head)");
        }
        if (params.head_length > 0.0f) return;
        // Measured where the axis is a fixed fraction of the length itself below the top, the first
        // such depth down from the top (iterated from just under it: each step goes down while the
        // head widens, and stops above a bun or shoulders lower down). Measured at a fraction of the
        // centre's depth instead, the length followed wherever the centre was: a --center in the
        // middle of the ponytail head's skull measured near the crown and put the hairline 10 units
        // higher, while the bounds' middle of that bust measured through the bun at the back and put
        // it 5 too low (a trial). 0.36 is where the bounds' middle of a head alone measured before
        // (the default head, ICT's face: 0.356 of their lengths below the top).
        constexpr double kDepth = 0.36;
        double h = 1e-3 * double(reach);
        for (int iteration = 0; iteration < 100; ++iteration) {
            const float3 a = top - up * float(h);
            float3 front, back;
            if (!outermost_hit(scalp, a + fwd * reach, a, front) || !outermost_hit(scalp, a - fwd * reach, a, back)) {
                // On a whole body the middle of the bounds is the belly, not the head: following the old
                // advice (--head-length) put the hairline across the eyebrows and down the neck (a trial
                // on MakeHuman). The axis is what is wrong; say where it runs.
                throw InvalidGeometry("hairline: could not measure the head's length: no scalp in front of or behind the head's axis at " +
                                      format_xyz(a) +
                                      (params.has_center ? std::string(" (through --center)")
                                                         : " (through the middle of the scalp's bounds, " + format_xyz(c) + ")") +
                                      "; give --center inside the head (on a bust or a whole body the middle of the bounds is not in it), "
                                      "then --head-length if it still fails");
            }
            length_fb = dot(front - back, fwd);
            if (!(length_fb > 0.0f)) break;
            const double next = kDepth * double(length_fb);
            if (std::fabs(next - h) <= 1e-5 * double(length_fb)) break;
            h = next;
        }
        if (!(length_fb > 0.0f)) throw InvalidGeometry("hairline: measured a head length <= 0; give --head-length");
    };
    find_top_and_length();

    // The head's middle at 0.36 of its length below the top, front to back and side to side: the
    // axis must run near it, the hairline's rays start there. The bounds' middle of a head alone is
    // within 0.06 lengths of it (the default head, ICT, Lee Perry-Smith, Sintel, Nefertiti, the
    // ponytail bust); MakeHuman's body's is 0.26 in front of it (the feet stand forward), and the
    // rays from there crossed the face (a trial). Without --center, the axis moves to the middle when
    // it is over 0.15 lengths off; a --center that far off is kept, and reported.
    // The scalp's reach ahead of and behind the axis along `d`, `depth` below the top (false where
    // a ray misses); the axis is moved, so this reads the current `c` and `top`.
    const auto reach_along = [&](double depth, const float3& d, float& ahead, float& behind) {
        const float3 a = top - up * float(depth);
        float3 front, back;
        if (!outermost_hit(scalp, a + d * reach, a, front) || !outermost_hit(scalp, a - d * reach, a, back)) return false;
        ahead = dot(front - a, d);
        behind = dot(a - back, d);
        return true;
    };
    float3 middle_offset(0.0f, 0.0f, 0.0f);
    if (float f, b, l, r; reach_along(0.36 * length_fb, fwd, f, b) && reach_along(0.36 * length_fb, side, l, r)) {
        middle_offset = fwd * (0.5f * (f - b)) + side * (0.5f * (l - r));
    }
    const bool off_middle = length(middle_offset) > 0.15f * length_fb;
    if (report) {
        *report = HairlineReport{};
        report->axis_off_middle = off_middle;
        report->middle_offset = middle_offset;
        report->suggested_center = top - up * float(0.5 * length_fb) + middle_offset;
    }
    if (off_middle && !params.has_center) {
        c = c + middle_offset;
        find_top_and_length();
        if (report) report->moved_axis = true;
    }
    if (report) {
        report->axis = c;
        // The head's middle front to back at the measuring depth, then the scalp's reach in front of
        // and behind it lower down, where a face and chin stand out and a neck is set back.
        float f0, b0, f1, b1, f2, b2;
        if (reach_along(0.36 * length_fb, fwd, f0, b0) && reach_along(0.8 * length_fb, fwd, f1, b1) && reach_along(0.9 * length_fb, fwd, f2, b2)) {
            const float middle = 0.5f * (f0 - b0);  // ahead of the axis
            report->measured = true;
            report->front = f1 + f2 - 2.0f * middle;
            report->back = b1 + b2 + 2.0f * middle;
        }
    }

    // Start at the nape (azimuth -180) so the seam of the closed curve sits at the back.
    const int n = params.points;
    auto degrees = [&](int i) { return -180.0 + 360.0 * i / n; };
    auto direction_at = [&](double deg) {
        const double rad = deg * kPi / 180.0;
        return fwd * float(std::cos(rad)) + side * float(std::sin(rad));
    };
    auto direction = [&](int i) { return direction_at(degrees(i)); };
    std::vector<double> drop(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) drop[size_t(i)] = drop_at(params, degrees(i)) * length_fb;
    // The key heights put the hairline "over the ears" at a fixed fraction of the head's length, but
    // ears sit higher on some heads: on the Lee Perry-Smith scan the outermost hit there was the ear's
    // bowl, and gathered hair rooted on the ear (a trial). On each side, the azimuths between the
    // temple and the nape whose hairline would pass below an ear's top span the ear; across that span
    // (and 4 degrees beyond) the hairline passes 2% of the head's length above the highest ear top.
    for (const int sign : {-1, 1}) {
        double ear_top = std::numeric_limits<double>::infinity(), first = 0.0, last = 0.0;
        // Scanned once a degree whatever --points is (per point, 100,000 points took 9 s), and no
        // lower than 0.9 head lengths (ears are higher; rays that miss a head trace all the way).
        for (int a = 66; a < 150; ++a) {
            const double deg = a;
            const double planned = std::min(drop_at(params, deg * sign) * length_fb, 0.9 * length_fb);
            const double t = ear_top_above(scalp, top, up, direction_at(deg * sign), reach, length_fb, planned);
            if (t < 0.0) continue;
            first = std::isfinite(ear_top) ? std::min(first, deg) : deg;
            last = std::isfinite(ear_top) ? std::max(last, deg) : deg;
            ear_top = std::min(ear_top, t);
        }
        // An ear spans 10-30 degrees of azimuth; bumps over a wider span are something else (the
        // sculpted curls of the Demosthenes bust raised its hairline over a third of the side).
        if (!std::isfinite(ear_top) || last - first > 40.0) continue;
        for (int i = 0; i < n; ++i) {
            const double deg = degrees(i) * sign;
            if (deg >= first - 4.0 && deg <= last + 4.0) drop[size_t(i)] = std::min(drop[size_t(i)], ear_top - 0.02 * length_fb);
        }
    }

    CurveSet out = CurveSet::from_counts(std::vector<int64_t>{n});
    auto P = out.positions_for_write();
    for (int i = 0; i < n; ++i) {
        const double deg = degrees(i);
        const float3 d = direction(i);
        const float3 a = top - up * float(drop[size_t(i)]);
        if (!outermost_hit(scalp, a + d * reach, a, P[i])) {
            throw InvalidGeometry("hairline: no scalp at azimuth " + format_number(deg) + " degrees, " + format_number(drop[size_t(i)]) +
                                  " below the top (is --up right, and the head closed there?)");
        }
    }
    out.add<int64_t>(Domain::Curve, attr::id)[0] = 0;
    return out;
}

}  // namespace groom
