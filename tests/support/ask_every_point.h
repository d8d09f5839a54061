// A scalp that asks every point in full: a ScalpField's answers with known_clear left at Surface's
// "ask", so a test can check that the ops come out the same without the voxels' shortcut
// (fields/clear_cells.h).
#pragma once

#include "fields/scalp_field.h"

namespace groom::test {

class AskEveryPoint final : public Surface {
public:
    explicit AskEveryPoint(const ScalpField& field) : field_(field) {}
    float distance(const float3& p) const override { return field_.distance(p); }
    float3 normal(const float3& p) const override { return field_.normal(p); }
    float3 closest_point(const float3& p) const override { return field_.closest_point(p); }
    float query(const float3& p, float3& n, float3& c) const override { return field_.query(p, n, c); }
    float distance_within(const float3& p, float reach) const override { return field_.distance_within(p, reach); }
    bool lipschitz() const override { return field_.lipschitz(); }
    bool first_intersection(const float3& a, const float3& b, float3& hit, float tolerance) const override
    {
        return field_.first_intersection(a, b, hit, tolerance);
    }

private:
    const ScalpField& field_;
};

}  // namespace groom::test
