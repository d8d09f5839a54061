#include "support/curve_turns.h"

#include <algorithm>
#include <cmath>

namespace groom::test {

std::vector<Turn> largest_turns(const CurveSet& cs)
{
    std::vector<Turn> turns;
    const auto P = cs.positions();
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const IndexRange r = cs.points_of(c);
        Turn worst;
        float3 last;
        bool have = false;
        for (int64_t i = r.begin; i + 1 < r.end; ++i) {
            const float3 s = P[size_t(i + 1)] - P[size_t(i)];
            if (!(length(s) > 0.0f)) continue;
            const float3 u = s / length(s);
            const double t = have ? std::acos(std::clamp(double(dot(last, u)), -1.0, 1.0)) * 180.0 / 3.141592653589793 : 0.0;
            if (t > worst.degrees) worst = {t, P[size_t(i)]};
            last = u, have = true;
        }
        turns.push_back(worst);
    }
    return turns;
}

}  // namespace groom::test
