#include "ops/edges.h"
#include "ops/root_uv.h"

#include "fields/keep_outside.h"
#include "kernel/error.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace groom {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Rng streams, one per purpose (kernel/rng.h).
enum Stream : uint64_t { kStation = 1, kDepth = 2, kHeight = 3, kShape = 4, kGroup = 5 };

double wrap180(double deg)
{
    deg = std::fmod(deg, 360.0);
    if (deg > 180.0) deg -= 360.0;
    if (deg <= -180.0) deg += 360.0;
    return deg;
}

double wrap360(double deg)
{
    deg = std::fmod(deg, 360.0);
    return deg < 0.0 ? deg + 360.0 : deg;
}

/// A piece of the hairline inside [from, to]: `offset` is the azimuth past `from`, increasing from a
/// to b.
struct Piece {
    double offset_a = 0.0, offset_b = 0.0;
    float3 a, b;
    double arc_begin = 0.0;  ///< arc length of the chosen part before this piece
    float length = 0.0f;
};

/// The head's azimuth frame: around `up` through `centre`, 0 at `forward`, positive toward up x forward.
struct AzimuthFrame {
    float3 centre, fwd, side;
    double degrees(const float3& p) const
    {
        const float3 v = p - centre;
        return std::atan2(double(dot(v, side)), double(dot(v, fwd))) * 180.0 / kPi;
    }
};

/// The parts of the closed polyline `pts` with azimuth in [from, from + width], clipped within
/// segments, in order of increasing azimuth past `from`, with their arc lengths.
std::vector<Piece> chosen_pieces(std::span<const float3> pts, const AzimuthFrame& frame, double from, double width)
{
    std::vector<Piece> pieces;
    const size_t n = pts.size();
    for (size_t i = 0; i < n; ++i) {
        const float3& A = pts[i];
        const float3& B = pts[(i + 1) % n];
        const double az_a = frame.degrees(A);
        const double d = wrap180(frame.degrees(B) - az_a);
        if (d == 0.0) continue;  // a segment along the axis direction carries no azimuth
        const double off = wrap360(az_a - from);
        const double lo = std::min(off, off + d), hi = std::max(off, off + d);
        // The chosen azimuths repeat every 360 degrees; a segment spans less than 180.
        for (int k = -1; k <= 1; ++k) {
            const double x0 = std::max(lo, 360.0 * k), x1 = std::min(hi, 360.0 * k + width);
            if (!(x1 > x0)) continue;
            Piece p;
            p.offset_a = x0 - 360.0 * k;
            p.offset_b = x1 - 360.0 * k;
            p.a = lerp(A, B, float((x0 - off) / d));
            p.b = lerp(A, B, float((x1 - off) / d));
            p.length = distance(p.a, p.b);
            if (p.length > 0.0f) pieces.push_back(p);
        }
    }
    std::sort(pieces.begin(), pieces.end(), [](const Piece& x, const Piece& y) { return x.offset_a < y.offset_a; });
    double arc = 0.0;
    for (Piece& p : pieces) {
        p.arc_begin = arc;
        arc += p.length;
    }
    return pieces;
}

/// Heading `h` (unit, tangent) turned by `angle` radians about the normal `n` (counter-clockwise seen
/// from outside).
float3 turn(const float3& h, const float3& n, double angle)
{
    return h * float(std::cos(angle)) + cross(n, h) * float(std::sin(angle));
}

/// A hair's shape in its root's tangent plane: arcs of constant geodesic curvature, one after the
/// other, and the heading it leaves its root with.
struct Shape {
    std::vector<double> arc_end;    ///< arc length where each arc ends (increasing)
    std::vector<double> curvature;  ///< signed curvature of each arc: + turns counter-clockwise about the normal
    double length = 0.0;            ///< the hair's length: the last arc goes on (or stops short) to reach it
    double theta0 = 0.0;            ///< initial heading, radians from `out` toward the hairline's tangent
    float height = 0.0f;

    /// The integral of the curvature over [a, b]: how far the heading turns there.
    double turning(double a, double b) const
    {
        double sum = 0.0, lo = 0.0;
        for (size_t k = 0; k < arc_end.size() && lo < b; ++k) {
            const double hi = k + 1 == arc_end.size() ? std::max(arc_end[k], b) : arc_end[k];
            sum += curvature[k] * std::max(0.0, std::min(b, hi) - std::max(a, lo));
            lo = hi;
        }
        return sum;
    }
};

/// Walks one hair on the scalp from `root` (on it) with normal `n0`; `out` and `tangent` span the
/// tangent plane there (tangent = n0 x out). Writes `points` positions, lifted by the height.
void walk_hair(const Surface& scalp, const float3& root, const float3& n0, const float3& out, const float3& tangent, const Shape& shape,
               int points, std::vector<float3>& dst)
{
    dst.resize(size_t(points));
    dst[0] = root;
    const double ds = shape.length / (points - 1);
    float3 h = out * float(std::cos(shape.theta0)) + tangent * float(std::sin(shape.theta0));
    float3 p = root, n = n0;
    for (int j = 1; j < points; ++j) {
        // Each step is a chord: it leaves along the heading turned by the curvature over the step's
        // first half and arrives turned by the second half, so a constant curvature puts every point
        // on the circle (the chords of an arc bisect its turning).
        const double s0 = (j - 1) * ds, s1 = j * ds, sm = 0.5 * (s0 + s1);
        h = turn(h, n, shape.turning(s0, sm));
        float3 n2, c;
        scalp.query(p + h * float(ds), n2, c);
        // Carry the heading into the new tangent plane (the least rotation for a small step).
        h = normalize(h - n2 * dot(h, n2), any_perpendicular(n2));
        h = turn(h, n2, shape.turning(sm, s1));
        p = c;
        n = n2;
        dst[size_t(j)] = c + n2 * shape.height;  // one step out the hair is at its full height
    }
}

}  // namespace

EdgeDirection parse_edge_direction(const std::string& name)
{
    if (name == "face") return EdgeDirection::Face;
    if (name == "along") return EdgeDirection::Along;
    if (name == "alternate") return EdgeDirection::Alternate;
    if (name == "random") return EdgeDirection::Random;
    throw InvalidParam("edges: `direction` must be face, along, alternate or random (got '" + name + "')");
}

const char* edge_direction_name(EdgeDirection d)
{
    switch (d) {
    case EdgeDirection::Face: return "face";
    case EdgeDirection::Along: return "along";
    case EdgeDirection::Alternate: return "alternate";
    case EdgeDirection::Random: return "random";
    }
    return "?";
}

void EdgesParams::validate() const
{
    auto positive = [](const char* name, float v) {
        if (!(v > 0.0f) || !std::isfinite(v)) {
            throw InvalidParam("edges: `" + std::string(name) + "` must be a finite number > 0 (got " + format_number(v) + ")");
        }
    };
    auto non_negative = [](const char* name, float v) {
        if (!(v >= 0.0f) || !std::isfinite(v)) {
            throw InvalidParam("edges: `" + std::string(name) + "` must be a finite number >= 0 (got " + format_number(v) + ")");
        }
    };
    if (!isfinite(up) || groom::length(up) == 0.0f) throw InvalidParam("edges: `up` must be a finite non-zero direction");
    if (!isfinite(forward) || groom::length(cross(up, forward)) < 1e-3f * groom::length(up) * groom::length(forward)) {
        throw InvalidParam("edges: `forward` must be a finite direction not parallel to `up`");
    }
    if (!std::isfinite(from) || std::fabs(from) > 360.0f) throw InvalidParam("edges: `from` must be in [-360, 360] degrees (got " + format_number(from) + ")");
    if (!std::isfinite(to) || !(to > from) || to - from > 360.0f) {
        throw InvalidParam("edges: `to` must be greater than `from` and at most 360 degrees past it (got from " + format_number(from) + ", to " +
                           format_number(to) + ")");
    }
    non_negative("depth", depth);
    if (count < 0) throw InvalidParam("edges: `count` must be >= 0 (got " + std::to_string(count) + ")");
    if (count > 10000000) throw InvalidParam("edges: `count` must be at most 10000000 (got " + std::to_string(count) + ")");
    positive("density", density);
    positive("length", length);
    positive("radius", radius);
    if (bends < 1 || bends > 16) throw InvalidParam("edges: `bends` must be in [1, 16] (got " + std::to_string(bends) + ")");
    positive("swoop", swoop);
    if (!(variation >= 0.0f && variation <= 0.9f)) throw InvalidParam("edges: `variation` must be in [0, 0.9] (got " + format_number(variation) + ")");
    non_negative("height", height);
    widths.validate("edges");
    if (points < 4 || points > 4096) throw InvalidParam("edges: `points` must be in [4, 4096] (got " + std::to_string(points) + ")");
    if (first_id < 0) throw InvalidParam("edges: `first_id` must be >= 0 (got " + std::to_string(first_id) + ")");
    if (kind < 0) throw InvalidParam("edges: `kind` must be >= 0 (got " + std::to_string(kind) + ")");
}

CurveSet edges(const Surface& scalp, const CurveSet& hairline, const EdgesParams& params, const HairRegion* region)
{
    params.validate();
    const auto hp = check_hairline(hairline, "edges: the hairline");

    const float3 up = normalize(params.up);
    AzimuthFrame frame;
    frame.fwd = normalize(params.forward - up * dot(params.forward, up));
    frame.side = cross(up, frame.fwd);
    for (const float3& p : hp) frame.centre += p;
    frame.centre = frame.centre * (1.0f / float(hp.size()));
    // Once around: the azimuth turns by a full circle (a curve on one side of the head, or a
    // hairline drawn around another axis, would make "from" and "to" meaningless).
    double turned = 0.0;
    for (size_t i = 0; i < hp.size(); ++i) turned += wrap180(frame.degrees(hp[(i + 1) % hp.size()]) - frame.degrees(hp[i]));
    if (std::fabs(std::fabs(turned) - 360.0) > 10.0) {
        throw InvalidGeometry("edges: the hairline must go once around the head (around `up` through its centroid); it turns " +
                              format_number(turned) + " degrees");
    }

    const std::vector<Piece> pieces = chosen_pieces(hp, frame, params.from, double(params.to) - double(params.from));
    const double total = pieces.empty() ? 0.0 : pieces.back().arc_begin + pieces.back().length;
    if (!(total > 0.0)) {
        throw InvalidGeometry("edges: no part of the hairline lies between azimuths " + format_number(params.from) + " and " + format_number(params.to) +
                              " degrees");
    }
    const double wanted = params.count > 0 ? double(params.count) : std::max(1.0, std::round(double(params.density) * total));
    if (wanted > 1e7) {
        throw InvalidParam("edges: `density` " + format_number(params.density) + " over " + format_number(total) + " of hairline gives " +
                           format_number(wanted) + " hairs; at most 10000000");
    }
    const int64_t ns = int64_t(wanted);
    // Before allocating: each hair's points are held twice (its own list, then the output: position
    // and width), and a hair costs its list and ids. The default density on a head modelled in
    // metres x 100 (1e4 x centimetres) asked for 5e6 hairs with no estimate (op fuzzer).
    check_memory("edges: " + std::to_string(ns) + " hairs (`density` x " + format_number(total) + " of hairline, or `count`) x " +
                     std::to_string(params.points) + " `points`",
                 double(ns) * (double(params.points) * 2.0 * 16.0 + 64.0), "lower `density`, `count` or `points` (or set `units_per_cm`)");
    const double spacing = total / double(ns);
    // Swoops are counted from the face's middle (azimuth 0) when the chosen part holds it, so the
    // pattern is symmetric there; else from `from`.
    double s_middle = 0.0;
    bool has_middle = false;
    const double middle_offset = wrap360(-double(params.from));
    for (const Piece& pc : pieces) {
        if (middle_offset >= pc.offset_a && middle_offset <= pc.offset_b && pc.offset_b > pc.offset_a) {
            s_middle = pc.arc_begin + pc.length * (middle_offset - pc.offset_a) / (pc.offset_b - pc.offset_a);
            has_middle = true;
            break;
        }
    }
    const int64_t first_group = int64_t(std::floor(-s_middle / params.swoop));
    const double w = params.swoop, r = params.radius;
    // Every arc of a hair in the middle of its swoop is r + w/2 in radius and turns by tau.
    const double tau = params.length / (params.bends * (r + 0.5 * w));

    // Each station's hair, or nothing when it is dropped; every station writes only its own slot.
    std::vector<std::vector<float3>> hairs(static_cast<size_t>(ns));
    std::vector<int32_t> group_of(static_cast<size_t>(ns));
    parallel_for(ns, 16, [&](int64_t b, int64_t e) {
        std::vector<float3> pts;
        for (int64_t k = b; k < e; ++k) {
            const uint64_t id = uint64_t(params.first_id + k);
            Rng station_rng(params.seed, id, kStation);
            const double s = (double(k) + station_rng.uniform_double()) * spacing;
            const auto it = std::upper_bound(pieces.begin(), pieces.end(), s, [](double v, const Piece& p) { return v < p.arc_begin; });
            const Piece& piece = *(it == pieces.begin() ? it : it - 1);
            const float u = piece.length > 0.0f ? std::clamp(float((s - piece.arc_begin) / piece.length), 0.0f, 1.0f) : 0.0f;
            const float3 on_line = lerp(piece.a, piece.b, u);
            const float3 along = normalize(piece.b - piece.a);  // toward increasing azimuth
            // The head's left (+) or right of the face's middle.
            const int side_sign = has_middle ? (s >= s_middle ? 1 : -1) : (frame.degrees(on_line) >= 0.0 ? 1 : -1);

            // Root: from the hairline, on the scalp, toward the haired side by depth x u.
            float3 n, c;
            scalp.query(on_line, n, c);
            float3 inward = normalize(cross(n, along - n * dot(along, n)), any_perpendicular(n));
            Rng depth_rng(params.seed, id, kDepth);
            const float depth = params.depth * depth_rng.uniform();
            const int sub = 4;
            for (int q = 0; q < sub && depth > 0.0f; ++q) {
                scalp.query(c + inward * (depth / sub), n, c);
                inward = normalize(inward - n * dot(inward, n), any_perpendicular(n));
            }
            const float3 root = c;
            if (region && region->inside_hairline(root) && !region->haired(root)) continue;  // on a parting's bare gap

            // The hair's frame at the root: out of the hairline (toward the face) and along it.
            const float3 tangent = normalize(along - n * dot(along, n), any_perpendicular(n));
            const float3 out = cross(tangent, n);  // n x out = tangent

            // Its swoop: which way it leans (+1 toward increasing azimuth) and how far the root is
            // from the swoop's end on that side, where the swirl's centre is.
            const int64_t g = int64_t(std::floor((s - s_middle) / w));
            group_of[size_t(k)] = int32_t(g - first_group);
            Rng group_rng(params.seed ^ 0x65646765ull, uint64_t(g - first_group), kGroup);
            const double group_tau = tau * (1.0 + 0.5 * params.variation * (2.0 * group_rng.uniform() - 1.0));
            int lean = side_sign;
            if (params.direction == EdgeDirection::Alternate) lean = ((g - first_group) % 2 == 0) ? 1 : -1;
            if (params.direction == EdgeDirection::Random) lean = group_rng.uniform() < 0.5f ? 1 : -1;
            const double to_end = std::clamp(lean > 0 ? (g + 1) * w - (s - s_middle) : (s - s_middle) - g * w, 0.0, w);

            Rng shape_rng(params.seed, id, kShape);
            const double v = params.variation;
            const double hair_tau = group_tau * (1.0 + 0.2 * v * (2.0 * shape_rng.uniform() - 1.0));
            const double ragged = 1.0 + v * (2.0 * shape_rng.uniform() - 1.0);
            const double heading_jitter = 0.1 * v * (2.0 * shape_rng.uniform() - 1.0);
            Rng height_rng(params.seed, id, kHeight);
            Shape shape;
            shape.height = params.height * (0.5f + 0.5f * height_rng.uniform());

            // Arcs: a swoop's hairs are parallel curves (a ribbon). The first arc circles the swirl's
            // centre, r past the swoop's end: radius r + to_end, so the swoop's hairs are concentric
            // there; each later arc bends the other way, where the inner hairs become the outer ones.
            // Along the hairline every hair is the middle one (the ribbon runs along its own length).
            auto build = [&](int sigma, double theta0) {
                shape.arc_end.clear();
                shape.curvature.clear();
                // A root inside the hairline first runs straight out to it, so every hair of a swoop
                // starts its arcs on the hairline, side by side.
                double end = depth;
                shape.arc_end.push_back(end);
                shape.curvature.push_back(0.0);
                for (int a = 0; a < params.bends; ++a) {
                    double radius = r + 0.5 * w;
                    if (params.direction != EdgeDirection::Along) radius = r + (a % 2 == 0 ? to_end : w - to_end);
                    end += hair_tau * radius;
                    shape.arc_end.push_back(end);
                    shape.curvature.push_back((a % 2 == 0 ? sigma : -sigma) / radius);
                }
                shape.length = depth + (end - depth) * ragged;
                shape.theta0 = theta0 + heading_jitter;
            };
            for (int attempt = 0; attempt < 2; ++attempt) {
                const int mirror = attempt == 0 ? 1 : -1;  // the mirror image about `out`, when the first crosses a parting
                if (params.direction == EdgeDirection::Along) {
                    // Along the hairline away from the middle on the mean: it leaves tilted by tau/2
                    // into the hairline and its first bend takes it out toward the face, so the wave
                    // runs along the hairline, half each side.
                    const int sigma = -side_sign * mirror;
                    build(sigma, mirror * side_sign * 0.5 * kPi - sigma * 0.5 * hair_tau);
                }
                else {
                    // Straight out of the hairline (a circle about a centre on the hairline leaves it
                    // at a right angle), bending toward the lean.
                    build(lean * mirror, 0.0);
                }
                walk_hair(scalp, root, n, out, tangent, shape, params.points, pts);
                bool crosses = false;
                if (region && region->num_partings() > 0) {
                    for (size_t j = 0; j + 1 < pts.size() && !crosses; ++j) crosses = region->crosses_parting(pts[j], pts[j + 1]);
                }
                if (!crosses) {
                    hairs[size_t(k)] = pts;
                    break;
                }
            }
        }
    });

    // Count, scan, fill.
    std::vector<int64_t> counts, station;
    for (int64_t k = 0; k < ns; ++k) {
        if (hairs[size_t(k)].empty()) continue;
        counts.push_back(int64_t(hairs[size_t(k)].size()));
        station.push_back(k);
    }
    CurveSet out = CurveSet::from_counts(counts);
    auto P = out.positions_for_write();
    auto ids = out.add<int64_t>(Domain::Curve, attr::id);
    auto kind = out.add<int32_t>(Domain::Curve, "kind");
    auto group = out.add<int32_t>(Domain::Curve, "group");
    parallel_for(int64_t(counts.size()), 256, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = out.points_of(size_t(c));
            const std::vector<float3>& src = hairs[size_t(station[size_t(c)])];
            std::copy(src.begin(), src.end(), P.begin() + r.begin);
            ids[size_t(c)] = params.first_id + station[size_t(c)];
            kind[size_t(c)] = params.kind;
            group[size_t(c)] = group_of[size_t(station[size_t(c)])];
        }
    });
    // Where the field's closest points disagree with its distances (a level set, a fold), a point
    // at a small height may read as inside: the one rule puts it back out (roots stay on the scalp).
    KeepOutside rule;
    rule.margin = 1e-4f * params.length;
    rule.max_steps = 4;
    keep_outside(out, scalp, rule);
    apply_hair_widths(out, params.widths);
    add_root_uvs(out, scalp);
    return out;
}

}  // namespace groom
