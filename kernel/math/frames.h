// Rotation-minimising frames along a polyline (Wang, Juttler, Zheng, Liu 2008, "Computation of
// Rotation Minimizing Frames", the double reflection method). Unlike Frenet frames they do not flip
// at inflections and do not spin where the curve is straight.
#pragma once

#include "kernel/math/vec.h"

#include <span>
#include <vector>

namespace groom {

/// An orthonormal frame: tangent t, normal n, binormal b = t x n.
struct Frame {
    float3 t{0, 1, 0}, n{1, 0, 0}, b{0, 0, 1};
};

/// Frames at each point of `pts`. `initial_normal` (need not be unit or perpendicular) fixes the
/// first frame's normal after projection onto the plane normal to the first tangent; when it is
/// (nearly) parallel to the tangent a perpendicular is chosen. Tangents: see polyline_tangents().
std::vector<Frame> rotation_minimising_frames(std::span<const float3> pts, const float3& initial_normal = {1, 0, 0});
/// The same into `frames` (resized); `tangents` is scratch (it ends holding the unit tangents).
void rotation_minimising_frames(std::span<const float3> pts, const float3& initial_normal, std::vector<Frame>& frames,
                                std::vector<float3>& tangents);

}  // namespace groom
