// Surface: what every op asks of the scalp. The real implementation is ScalpField (an OpenVDB level
// set, fields/scalp_field.h); AnalyticSphere and AnalyticPlane answer exactly and are what tests
// check ops against. All queries are const and thread-safe.
#pragma once

#include "kernel/math/vec.h"

namespace groom {

class Surface {
public:
    virtual ~Surface() = default;

    /// Signed distance from p to the surface, scene units; negative inside (behind the oriented normals).
    virtual float distance(const float3& p) const = 0;
    /// Unit outward normal of the surface at its point closest to p.
    virtual float3 normal(const float3& p) const = 0;
    /// The closest point on the surface to p.
    virtual float3 closest_point(const float3& p) const = 0;
    /// Signed distance, unit normal and closest point in one call; the same answers as the three
    /// above. The default asks each; ScalpField answers from one read of its grid.
    virtual float query(const float3& p, float3& normal, float3& closest) const;

    /// The signed distance where it is shorter than `reach` (scene units, >= 0); beyond, possibly
    /// only a bound: a value of the same sign, at least `reach` and at most the distance in size.
    /// So `distance_within(p, r) < t` is `distance(p) < t` for every t in (-r, r]: what a caller
    /// that compares with a clearance needs, where it needs no value. ScalpField answers most points
    /// outside its narrow band this way without an exact search of the mesh; the default is distance(p).
    virtual float distance_within(const float3& p, float reach) const;
    /// True only where `distance_within(p, need) >= need` is already known without asking it
    /// (need >= 0); false means "ask". The rule that keeps hair out of the scalp asks this first
    /// of every point (fields/keep_outside.h). ScalpField knows it for most voxels near the head
    /// from one worked-out answer per voxel; the default knows nothing.
    virtual bool known_clear(const float3& /*p*/, float /*need*/) const { return false; }

    bool inside(const float3& p) const { return distance_within(p, 0.0f) < 0.0f; }

    /// True when the distance is 1-Lipschitz, |distance(p) - distance(q)| <= |p - q| (a true signed
    /// distance: the analytic surfaces, a closed mesh); false where its sign jumps away from the
    /// surface (the 1/2 surface across a mesh's opening, overlapping shells that disagree on inside),
    /// which a path can cross without passing near the surface. Code that skips queries by that
    /// bound must ask this first.
    virtual bool lipschitz() const { return true; }

    /// How far this surface may lie from the mesh it stands for, scene units: 0 for the analytic
    /// surfaces and a mesh answered exactly; for a level set, how far its interpolated zero crossing
    /// strays from the user's mesh where that has detail finer than a voxel (ScalpField). Hair laid
    /// on the scalp is lifted by it, so that it lies on the mesh a renderer draws, not under it.
    virtual float surface_tolerance() const { return 0.0f; }

    /// First point where the segment a->b enters the surface (sign change from outside to inside),
    /// accurate to `tolerance` (scene units; 0 = a default relative to the segment). Returns false
    /// when the segment never crosses into the inside. The default marches by the distance bound.
    virtual bool first_intersection(const float3& a, const float3& b, float3& hit, float tolerance = 0.0f) const;

    /// True when the surface has texture coordinates (a scalp mesh with UVs): then surface_uv answers.
    virtual bool has_uvs() const { return false; }
    /// The texture coordinate at the surface point closest to p, interpolated barycentrically on
    /// the mesh triangle holding it (face-varying, so seams keep both sides' values). Returns false
    /// where the surface has none; u, v untouched then.
    virtual bool surface_uv(const float3& /*p*/, float& /*u*/, float& /*v*/) const { return false; }
};

/// The exact sphere |p - center| = radius, outside = away from the center.
class AnalyticSphere final : public Surface {
public:
    AnalyticSphere(const float3& center, float radius) : center_(center), radius_(radius) {}
    float distance(const float3& p) const override { return groom::distance(p, center_) - radius_; }
    float3 normal(const float3& p) const override { return normalize(p - center_, float3(0, 1, 0)); }
    float3 closest_point(const float3& p) const override { return center_ + normal(p) * radius_; }
    const float3& center() const { return center_; }
    float radius() const { return radius_; }

private:
    float3 center_;
    float radius_;
};

/// The exact plane through `origin` with unit normal `normal` (outside = the side the normal faces).
class AnalyticPlane final : public Surface {
public:
    AnalyticPlane(const float3& origin, const float3& normal) : origin_(origin), normal_(normalize(normal)) {}
    float distance(const float3& p) const override { return dot(p - origin_, normal_); }
    float3 normal(const float3&) const override { return normal_; }
    float3 closest_point(const float3& p) const override { return p - normal_ * distance(p); }

private:
    float3 origin_, normal_;
};

}  // namespace groom
