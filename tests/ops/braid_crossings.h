// Test helper: what a person sees in a braid, measured from braid() output alone. Every strand
// centreline is expressed in its guide's local frame (along, lateral, up), and the crossings are
// found where two strands swap sides in the lateral direction, as seen looking down the up axis.
// At each crossing the strand with the larger height is on top. Nothing here reads the op's
// formulas or constants.
#pragma once

#include "kernel/curve_set.h"
#include "kernel/math/polyline.h"
#include "kernel/math/vec.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace groom::test {

/// A strand sample in its guide's frame.
struct Local {
    double along = 0.0, lateral = 0.0, up = 0.0;
};

/// The frame of the guide at arc-length fraction t: origin, lateral axis, up axis (unit, orthogonal).
struct GuideFrame {
    float3 origin, lateral, up;
};

struct Crossing {
    double t = 0.0;        ///< arc-length fraction of the guide
    int top = -1, bottom = -1;
    double lateral = 0.0;  ///< where across the braid it happens
    double gap = 0.0;      ///< height of top minus height of bottom
    bool top_inward = false, bottom_inward = false;  ///< moving toward the braid's middle (|lateral| falling)
};

struct WeaveReading {
    std::vector<std::vector<Local>> strands;  ///< [strand][sample]
    std::vector<Crossing> crossings;          ///< by t
    std::vector<std::string> sequence;        ///< per strand: 'O' / 'U' at its crossings, root to tip
    std::map<std::pair<int, int>, int> pair_crossings;
    int max_run = 0;  ///< longest run of O or U in any strand's sequence
};

/// Strands of one guide: output curves [first, first + n), all with the same sample count, sample j
/// at arc-length fraction j / (S - 1) of the guide. `frame(t)` gives the guide's frame there.
inline WeaveReading read_weave(const CurveSet& cs, int64_t first, int n, const std::function<GuideFrame(double)>& frame)
{
    WeaveReading w;
    const auto P = cs.positions();
    const int64_t S = cs.points_in(first);
    w.strands.assign(n, std::vector<Local>(S));
    for (int64_t j = 0; j < S; ++j) {
        const double t = double(j) / double(S - 1);
        const GuideFrame f = frame(t);
        for (int i = 0; i < n; ++i) {
            const float3 d = P[cs.points_of(first + i).begin + j] - f.origin;
            w.strands[i][j] = {t, double(dot(d, f.lateral)), double(dot(d, f.up))};
        }
    }
    w.sequence.assign(n, {});
    for (int a = 0; a < n; ++a) {
        for (int b = a + 1; b < n; ++b) {
            // Walk the lateral difference; a crossing is a change of sign between two samples where it is
            // not zero (samples exactly on a crossing are passed over and the crossing put at them).
            const auto diff = [&](int64_t j) { return w.strands[a][j].lateral - w.strands[b][j].lateral; };
            int64_t last = -1;
            for (int64_t j = 0; j < S; ++j) {
                const double dj = diff(j);
                if (dj == 0.0) continue;
                if (last < 0 || (dj > 0.0) == (diff(last) > 0.0)) {
                    last = j;
                    continue;
                }
                // Between samples j0 and j0 + 1 at fraction f.
                int64_t j0 = last;
                double f = 0.0;
                if (j == last + 1) f = diff(last) / (diff(last) - dj);
                else j0 = (last + j) / 2;  // zeros between: the middle one
                last = j;
                const int64_t j1 = std::min(j0 + 1, S - 1);
                const auto lerp = [&](int s, auto get) {
                    return get(w.strands[s][j0]) + f * (get(w.strands[s][j1]) - get(w.strands[s][j0]));
                };
                const auto up = [](const Local& l) { return l.up; };
                const auto lat = [](const Local& l) { return l.lateral; };
                const double ua = lerp(a, up), ub = lerp(b, up);
                Crossing c;
                c.t = w.strands[a][j0].along + f * (w.strands[a][j1].along - w.strands[a][j0].along);
                c.top = ua >= ub ? a : b;
                c.bottom = ua >= ub ? b : a;
                c.lateral = lerp(a, lat);
                c.gap = std::fabs(ua - ub);
                // Moving toward the braid's middle: |lateral| falls across the crossing.
                const auto inward = [&](int s) {
                    const int64_t lo = std::max<int64_t>(j0 - 1, 0), hi = std::min<int64_t>(j1 + 1, S - 1);
                    return std::fabs(w.strands[s][hi].lateral) < std::fabs(w.strands[s][lo].lateral);
                };
                c.top_inward = inward(c.top);
                c.bottom_inward = inward(c.bottom);
                w.crossings.push_back(c);
                ++w.pair_crossings[{a, b}];
            }
        }
    }
    std::sort(w.crossings.begin(), w.crossings.end(), [](const Crossing& x, const Crossing& y) { return x.t < y.t; });
    for (const Crossing& c : w.crossings) {
        w.sequence[c.top] += 'O';
        w.sequence[c.bottom] += 'U';
    }
    for (const std::string& s : w.sequence) {
        int run = 0;
        for (size_t k = 0; k < s.size(); ++k) {
            run = k > 0 && s[k] == s[k - 1] ? run + 1 : 1;
            w.max_run = std::max(w.max_run, run);
        }
    }
    return w;
}

/// Closest distance between two polylines (segment to segment, exact).
inline double polyline_distance(const CurveSet& cs, int64_t a, int64_t b)
{
    const auto P = cs.positions();
    const IndexRange ra = cs.points_of(a), rb = cs.points_of(b);
    double best = std::numeric_limits<double>::infinity();
    for (int64_t i = ra.begin; i + 1 < ra.end; ++i)
        for (int64_t j = rb.begin; j + 1 < rb.end; ++j) best = std::min(best, std::sqrt(segment_distance_sq(P[i], P[i + 1], P[j], P[j + 1])));
    return best;
}

}  // namespace groom::test
