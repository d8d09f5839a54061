#include "ops/braid_weave.h"

#include "kernel/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace groom {

namespace {

constexpr double kPi = std::numbers::pi;

struct PatternName {
    BraidPattern pattern;
    const char* name;
};
constexpr std::array<PatternName, 6> kPatterns{{{BraidPattern::Plait, "plait"},
                                                {BraidPattern::Fishtail, "fishtail"},
                                                {BraidPattern::Twist, "twist"},
                                                {BraidPattern::Rope, "rope"},
                                                {BraidPattern::Round, "round"},
                                                {BraidPattern::Lissajous, "lissajous"}}};

/// x mod m in [0, m), in double so a large phase keeps its fraction.
double wrap(double x, double m)
{
    double r = std::fmod(x, m);
    if (r < 0.0) r += m;
    return r >= m ? 0.0 : r;
}

/// Slot sequences of a flat plait: odd-even transposition. Strand 0 walks 0, 1, ..., N-1, rests one
/// step at the edge, walks back and rests again (2N steps); strand i is strand 0 two steps later, so at
/// every step the strands occupy distinct slots and exactly the neighbours of alternate pairs swap.
std::vector<std::vector<int>> plait_slots(int n)
{
    const int steps = 2 * n;
    std::vector<int> walk(steps);
    for (int k = 0; k < n; ++k) {
        walk[k] = k;
        walk[n + k] = n - 1 - k;
    }
    std::vector<std::vector<int>> slots(n, std::vector<int>(steps));
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < steps; ++k) slots[i][k] = walk[(k + 2 * i) % steps];
    return slots;
}

/// Slot sequences of a fishtail (N even): left section slots [0, h), right [h, N). Even steps: the
/// outermost left piece crosses its section to the inside of the right one (the others of the left
/// move out by one slot); odd steps: the outermost right piece crosses to the inside of the left (the
/// others of the right move out by one). The order of strands across the slots after each step is the
/// slot sequence; after 2N steps every strand is back where it started.
std::vector<std::vector<int>> fishtail_slots(int n)
{
    const int h = n / 2, steps = 2 * n;
    std::vector<int> order(n);  // order[slot] = strand
    for (int s = 0; s < n; ++s) order[s] = s;
    std::vector<std::vector<int>> slots(n, std::vector<int>(steps));
    for (int k = 0; k < steps; ++k) {
        for (int s = 0; s < n; ++s) slots[order[s]][k] = s;
        std::vector<int> next;
        next.reserve(n);
        if (k % 2 == 0) {  // left outer piece -> inside of the right section
            next.assign(order.begin() + 1, order.begin() + h);
            next.push_back(order[0]);
            next.insert(next.end(), order.begin() + h, order.end());
        }
        else {  // right outer piece -> inside of the left section
            next.assign(order.begin(), order.begin() + h - 1);
            next.push_back(order[n - 1]);
            next.insert(next.end(), order.begin() + h - 1, order.end() - 1);
        }
        order = std::move(next);
    }
    for (int s = 0; s < n; ++s) {
        if (order[s] != s) throw Error("braid: fishtail slot sequence is not periodic");
    }
    return slots;
}

/// Cosine ease from a to b, v in [0, 1]: level at both ends.
double ease(double a, double b, double v) { return a + (b - a) * 0.5 * (1.0 - std::cos(kPi * v)); }

}  // namespace

std::vector<BraidPattern> braid_patterns()
{
    std::vector<BraidPattern> out;
    for (const PatternName& p : kPatterns) out.push_back(p.pattern);
    return out;
}

const char* braid_pattern_name(BraidPattern p)
{
    for (const PatternName& q : kPatterns)
        if (q.pattern == p) return q.name;
    return "?";
}

std::string braid_pattern_list()
{
    std::string s;
    for (const PatternName& p : kPatterns) s += (s.empty() ? "" : "|") + std::string(p.name);
    return s;
}

int default_strands(BraidPattern p)
{
    switch (p) {
    case BraidPattern::Fishtail: return 8;
    case BraidPattern::Twist: return 2;
    case BraidPattern::Round: return 4;
    default: return 3;
    }
}

void validate_pattern_strands(BraidPattern p, int strands)
{
    const std::string got = " (got `strands` " + std::to_string(strands) + ")";
    // The weave's crossings and closest approach cost about N^3 (pairs times steps, a step per
    // strand): 32 strands take 0.5 s per guide length, 198 took minutes (found by the op fuzzer).
    // Hair is not braided with more than a few dozen strands.
    if (strands > kMaxStrands) throw InvalidParam("braid: `strands` must be <= " + std::to_string(kMaxStrands) + got);
    switch (p) {
    case BraidPattern::Fishtail:
        if (strands < 4 || strands % 2 != 0) throw InvalidParam("braid: `pattern` fishtail needs an even `strands` >= 4" + got);
        break;
    case BraidPattern::Round:
        if (strands < 4 || strands % 2 != 0) throw InvalidParam("braid: `pattern` round needs an even `strands` >= 4" + got);
        break;
    case BraidPattern::Twist:
        if (strands != 2) throw InvalidParam("braid: `pattern` twist has 2 strands; use `pattern` rope for more" + got);
        break;
    default:
        if (strands < 2) throw InvalidParam("braid: `strands` must be >= 2" + got);
    }
}

BraidWeave::BraidWeave(BraidPattern pattern, int strands, BraidHand hand)
    : pattern_(pattern), n_(strands), hand_sign_(hand == BraidHand::Under ? -1 : 1)
{
    if (hand == BraidHand::Auto) throw Error("braid: weave built with an unresolved hand");
    validate_pattern_strands(pattern, strands);
    if (pattern_ != BraidPattern::Plait && pattern_ != BraidPattern::Fishtail) return;

    slots_ = pattern_ == BraidPattern::Plait ? plait_slots(n_) : fishtail_slots(n_);
    steps_ = int(slots_[0].size());
    events_.assign(n_, {});
    // Find every crossing (lateral paths equal) step by step, then let the pattern say who is on top.
    for (int k = 0; k < steps_; ++k) {
        const int k1 = (k + 1) % steps_;
        for (int i = 0; i < n_; ++i) {
            for (int j = i + 1; j < n_; ++j) {
                const int di0 = slots_[i][k] - slots_[j][k], di1 = slots_[i][k1] - slots_[j][k1];
                if ((di0 > 0) == (di1 > 0)) continue;  // same order after the step: no crossing
                // Bisect x_i - x_j on the step (slots differ at both ends, so the sign changes once).
                double lo = k, hi = k + 1.0;
                const double s0 = di0 > 0 ? 1.0 : -1.0;
                for (int it = 0; it < 50; ++it) {
                    const double mid = 0.5 * (lo + hi);
                    const double d = slot_lateral(i, mid) - slot_lateral(j, mid);
                    ((d > 0.0 ? 1.0 : -1.0) == s0 ? lo : hi) = mid;
                }
                const double tau = 0.5 * (lo + hi);
                // r moves right (to the higher slot), l moves left.
                const bool i_right = slots_[i][k1] > slots_[i][k];
                const int r = i_right ? i : j, l = i_right ? j : i;
                double r_value = 0.0;  // +1: the right-mover is on top (before the hand is applied)
                if (pattern_ == BraidPattern::Plait) {
                    // Each strand alternates along its walk from an edge: the k-th crossing of a walk
                    // (k = 0 at the edge) passes under for even k. A walk from the left edge is at its
                    // a-th crossing on pair (a, a+1), one from the right edge at its (N-2-a)-th. For odd
                    // N the two rules agree; for even N they disagree on every pair, so the left half
                    // and the middle pair follow the right-mover and the right half the left-mover
                    // (a strand then stays over or under for two crossings at the middle or an edge).
                    const int a = std::min(slots_[r][k], slots_[r][k1]);
                    const bool right_half = 2 * a > n_ - 2;
                    const bool r_under = right_half ? ((n_ - 2 - a) % 2 != 0) : (a % 2 == 0);
                    r_value = r_under ? -1.0 : 1.0;
                }
                else {
                    // Fishtail: the piece crossing from the outside of its section is the one that
                    // left the outer slot (slot 0 on even steps, N-1 on odd steps); it passes on top.
                    const int crosser = k % 2 == 0 ? (slots_[i][k] == 0 ? i : j) : (slots_[i][k] == n_ - 1 ? i : j);
                    r_value = crosser == r ? 1.0 : -1.0;
                }
                // Under-hand flips every crossing (see BraidHand): hand_sign_ = +1 over, -1 under.
                // The rules above are written for the under hand.
                if (pattern_ == BraidPattern::Fishtail) r_value *= hand_sign_;
                else r_value *= -hand_sign_;
                events_[r].push_back({tau, r_value});
                events_[l].push_back({tau, -r_value});
            }
        }
    }
    for (auto& ev : events_) {
        std::sort(ev.begin(), ev.end(), [](const Event& a, const Event& b) { return a.tau < b.tau; });
        if (ev.empty()) throw Error("braid: a strand of the weave never crosses another");
    }
}

double BraidWeave::slot_lateral(int i, double tau) const
{
    const int k = std::min(int(tau), steps_ - 1);
    const double v = tau - k;
    const auto& s = slots_[i];
    const auto pos = [&](int kk) { return -1.0 + 2.0 * double(s[(kk % steps_ + steps_) % steps_]) / (n_ - 1); };
    // Periodic Catmull-Rom through the slots: passes each slot at its step, smooth through the turns.
    const double p0 = pos(k), p1 = pos(k + 1), m0 = 0.5 * (p1 - pos(k - 1)), m1 = 0.5 * (pos(k + 2) - p0);
    const double v2 = v * v, v3 = v2 * v;
    return (2 * v3 - 3 * v2 + 1) * p0 + (v3 - 2 * v2 + v) * m0 + (-2 * v3 + 3 * v2) * p1 + (v3 - v2) * m1;
}

WeaveOffset BraidWeave::slotted(int i, double u) const
{
    const double tau = wrap(u, 1.0) * steps_;
    WeaveOffset o;
    o.x = slot_lateral(i, tau);
    const auto& ev = events_[i];
    // Bracketing crossings, periodic: the last one at or before tau and the next after it.
    const auto it = std::upper_bound(ev.begin(), ev.end(), tau, [](double t, const Event& e) { return t < e.tau; });
    const Event& e1 = it == ev.end() ? ev.front() : *it;
    const Event& e0 = it == ev.begin() ? ev.back() : *(it - 1);
    double t0 = e0.tau, t1 = e1.tau;
    if (t0 > tau) t0 -= steps_;
    if (t1 <= tau) t1 += steps_;
    if (t1 <= t0) t1 = t0 + steps_;  // a single crossing per period
    o.y = ease(e0.value, e1.value, (tau - t0) / (t1 - t0));
    o.press = o.y * o.y;
    return o;
}

WeaveOffset BraidWeave::at(int i, double u) const
{
    switch (pattern_) {
    case BraidPattern::Plait:
    case BraidPattern::Fishtail: return slotted(i, u);
    case BraidPattern::Rope:
    case BraidPattern::Twist: {
        // Plies on a helix of radius 1, evenly spaced, one turn per knot.
        const double theta = 2.0 * kPi * (hand_sign_ * wrap(u, 1.0) + double(i) / n_);
        return {std::cos(theta), std::sin(theta), 0.5};
    }
    case BraidPattern::Round: {
        // Maypole braid: h strands turn one way, h the other; at every 1/(2h) knot each meets one of
        // the other set, passing outside and inside by turns (the radius swings by eps).
        const int h = n_ / 2;
        const double uu = wrap(u, 1.0);
        const bool cw = i < h;
        const double theta = cw ? 2.0 * kPi * (uu + double(i) / h) : 2.0 * kPi * (-uu + (double(i - h) + 0.5) / h);
        const double c = hand_sign_ * (cw ? 1.0 : -1.0) * std::cos(kPi * (2.0 * h * uu - 0.5));
        const double r = 1.0 + 0.5 * touching_width() * c;
        return {r * std::cos(theta), r * std::sin(theta), c * c};
    }
    case BraidPattern::Lissajous: {
        // Sec. 2.1 as written: x = sin(2 pi (F alpha + delta)), y = sin(2 pi (F beta - delta)),
        // beta = alpha / 2, delta = i / N; u = F alpha. y repeats every two knots.
        const double delta = double(i) / n_;
        const double px = wrap(u + delta, 1.0), py = wrap(0.5 * u - delta, 1.0);
        const double y = std::sin(2.0 * kPi * py);
        return {std::sin(2.0 * kPi * px), y, y * y};
    }
    }
    return {};
}

double BraidWeave::touching_width() const
{
    switch (pattern_) {
    case BraidPattern::Plait:
    case BraidPattern::Fishtail: return 2.0 / (n_ - 1);
    case BraidPattern::Rope:
    case BraidPattern::Twist: return 2.0 * std::sin(kPi / n_);
    case BraidPattern::Round: return std::min(1.0, 4.0 / n_);
    case BraidPattern::Lissajous: return 2.0 / n_;
    }
    return 1.0;
}

double BraidWeave::touching_height() const
{
    switch (pattern_) {
    case BraidPattern::Plait:
    case BraidPattern::Fishtail: return 0.5 * touching_width();
    case BraidPattern::Lissajous: return 0.5;
    default: return 1.0;
    }
}

double BraidWeave::min_separation(double A, double B, double L) const
{
    // Samples per knot, and how far along (in knots) a neighbour can come closest: within a couple of
    // weave steps for a plait or fishtail, within half a turn for the helical patterns.
    const bool slotted_pattern = steps_ > 0;
    // 12 samples a step find the closest approach to within a few percent (the centrelines are smooth
    // at that scale); the caller keeps a 0.85 margin on top.
    const int per_knot = slotted_pattern ? 12 * steps_ : 96;
    const int window = slotted_pattern ? 30 : per_knot / 2;
    const int period = pattern_ == BraidPattern::Lissajous ? 2 : 1;
    const int total = per_knot * period;
    struct Q {
        double a, x, y;
    };
    std::vector<std::vector<Q>> pts(n_, std::vector<Q>(total));
    for (int i = 0; i < n_; ++i) {
        for (int k = 0; k < total; ++k) {
            const double u = double(k) / per_knot;
            const WeaveOffset o = at(i, u);
            pts[i][k] = {u * L, o.x * A, o.y * B};
        }
    }
    double best2 = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n_; ++i) {
        for (int j = i + 1; j < n_; ++j) {
            for (int k = 0; k < total; ++k) {
                const Q& p = pts[i][k];
                for (int d = -window; d <= window; ++d) {
                    const int kk = ((k + d) % total + total) % total;
                    const Q& q = pts[j][kk];
                    const double da = p.a - (q.a + double((k + d - kk)) / per_knot * L);
                    const double dx = p.x - q.x, dy = p.y - q.y;
                    best2 = std::min(best2, da * da + dx * dx + dy * dy);
                }
            }
        }
    }
    return std::sqrt(best2);
}

int BraidWeave::winding() const
{
    if (pattern_ == BraidPattern::Rope || pattern_ == BraidPattern::Twist) return hand_sign_;
    return 0;
}

}  // namespace groom
