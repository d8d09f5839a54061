// Cameras and named views: the orthonormal camera basis, the views' cameras and names, camera checks,
// and framing a scene to fit. Apart from the rasteriser: this decides where to look, not how to draw.
#include "ops/render_impl.h"

#include <algorithm>
#include <cmath>

namespace groom {

using namespace render_detail;

namespace {

bool finite3(const float3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

namespace render_detail {

Basis camera_basis(const Camera& cam)
{
    Basis b;
    b.forward = normalize(cam.target - cam.eye);
    float3 up = normalize(cam.up, float3(0, 1, 0));
    // An up along the view direction (looking straight down with +Y up) has no unique right: pick
    // the world axis least aligned with the view instead of failing.
    if (std::fabs(dot(up, b.forward)) > 0.999f) up = std::fabs(b.forward.z) < 0.9f ? float3(0, 0, 1) : float3(0, 1, 0);
    b.right = normalize(cross(b.forward, up));
    b.up = cross(b.right, b.forward);
    return b;
}

}  // namespace render_detail

std::string_view view_name(View view)
{
    switch (view) {
    case View::Front: return "front";
    case View::Back: return "back";
    case View::Left: return "left";
    case View::Right: return "right";
    case View::Top: return "top";
    case View::ThreeQuarter: return "three-quarter";
    }
    return "front";
}

void Camera::validate() const
{
    if (!finite3(eye) || !finite3(target) || !finite3(up)) {
        throw InvalidParam("render: `camera` values must be finite (got eye " + fmt(eye.x) + "," + fmt(eye.y) + "," + fmt(eye.z) +
                           ", target " + fmt(target.x) + "," + fmt(target.y) + "," + fmt(target.z) + ")");
    }
    const float size = std::max({1.0f, length(eye), length(target)});
    if (distance(eye, target) <= 1e-6f * size) {
        throw InvalidParam("render: `camera` eye and target must differ (both are " + fmt(eye.x) + "," + fmt(eye.y) + "," +
                           fmt(eye.z) + ")");
    }
    if (length(up) == 0.0f) throw InvalidParam("render: camera up vector must not be zero");
    if (!std::isfinite(fov_degrees) || fov_degrees < 0.0f || fov_degrees >= 170.0f) {
        throw InvalidParam("render: `fov` must be in (0, 170) degrees, or 0 for orthographic (got " + fmt(fov_degrees) + ")");
    }
    if (!std::isfinite(ortho_height) || ortho_height < 0.0f) {
        throw InvalidParam("render: orthographic height must be >= 0 scene units (0 = fit; got " + fmt(ortho_height) + ")");
    }
}

Camera view_camera(View view)
{
    Camera c;
    c.target = {0, 0, 0};
    c.up = {0, 1, 0};
    switch (view) {
    case View::Front: c.eye = {0, 0, 1}; break;
    case View::Back: c.eye = {0, 0, -1}; break;
    case View::Left: c.eye = {1, 0, 0}; break;
    case View::Right: c.eye = {-1, 0, 0}; break;
    case View::Top:
        c.eye = {0, 1, 0};
        c.up = {0, 0, 1};  // face at the top of the picture
        break;
    case View::ThreeQuarter: c.eye = normalize(float3(0.75f, 0.3f, 1.0f)); break;
    }
    return c;
}

Camera frame_camera(const RenderScene& scene, const Camera& camera, float aspect, float margin)
{
    camera.validate();
    if (camera.fov_degrees > 0.0f || camera.ortho_height > 0.0f) return camera;
    const Basis b = camera_basis(camera);
    float lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
    auto extend = [&](const float3& p) {
        const float3 v = p - camera.target;
        const float x = dot(v, b.right), y = dot(v, b.up);
        lo_x = std::min(lo_x, x);
        hi_x = std::max(hi_x, x);
        lo_y = std::min(lo_y, y);
        hi_y = std::max(hi_y, y);
    };
    if (scene.mesh)
        for (const float3& p : scene.mesh->points) extend(p);
    for (const CurveSet* c : scene.curves)
        for (const float3& p : c->positions()) extend(p);
    Camera out = camera;
    if (!(lo_x <= hi_x)) {  // nothing drawn
        out.ortho_height = 1.0f;
        return out;
    }
    const float3 shift = b.right * (0.5f * (lo_x + hi_x)) + b.up * (0.5f * (lo_y + hi_y));
    out.target = camera.target + shift;
    out.eye = camera.eye + shift;
    const float need = std::max(hi_y - lo_y, (hi_x - lo_x) / aspect);
    out.ortho_height = std::max(need, 1e-6f) / (1.0f - 2.0f * margin);
    return out;
}

}  // namespace groom
