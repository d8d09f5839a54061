#include "ops/render.h"

#include "kernel/error.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace groom {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr int kTile = 32;                       // tile side in samples: a few KB of z-buffer per task
constexpr int kMaxSide = 16384;                 // pixels per side of one view
constexpr int64_t kMaxSamples = int64_t(1) << 27;  // 128 M samples = 1 GiB of colour + depth

std::string fmt(float v) { return format_number(v); }

bool finite3(const float3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check_color(const char* option, const float3& c)
{
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(c[i]) || c[i] < 0.0f || c[i] > 1.0f) {
            throw InvalidParam(std::string("render: ") + option + " components must be in [0, 1] (got " + fmt(c.x) + "," +
                               fmt(c.y) + "," + fmt(c.z) + ")");
        }
    }
}

uint32_t pack(const float3& c)
{
    auto u8 = [](float v) { return static_cast<uint32_t>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); };
    return u8(c.x) | (u8(c.y) << 8) | (u8(c.z) << 16);
}
float3 unpack(uint32_t c)
{
    return {float(c & 255u) / 255.0f, float((c >> 8) & 255u) / 255.0f, float((c >> 16) & 255u) / 255.0f};
}

/// Orthonormal camera basis: forward (into the picture), right, up.
struct Basis {
    float3 forward, right, up;
};

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

/// Maps scene points to sample coordinates (x right, y down, pixel centres at i + 0.5) and depth.
struct Projector {
    Basis basis;
    float3 origin;  // eye (perspective) or target (orthographic)
    bool perspective = false;
    float scale = 1.0f;  // orthographic: samples per scene unit; perspective: samples at unit depth
    float cx = 0.0f, cy = 0.0f;
    float near = 0.0f;

    Projector(const Camera& cam, int width_samples, int height_samples)
    {
        basis = camera_basis(cam);
        perspective = cam.fov_degrees > 0.0f;
        cx = 0.5f * float(width_samples);
        cy = 0.5f * float(height_samples);
        if (perspective) {
            origin = cam.eye;
            scale = cy / std::tan(0.5f * cam.fov_degrees * kPi / 180.0f);
            near = 1e-3f * distance(cam.eye, cam.target);
        }
        else {
            origin = cam.target;
            scale = float(height_samples) / cam.ortho_height;
        }
    }

    /// False when the point is behind the near plane (perspective only).
    bool project(const float3& p, float& sx, float& sy, float& depth, float& samples_per_unit) const
    {
        const float3 v = p - origin;
        const float x = dot(v, basis.right), y = dot(v, basis.up);
        depth = dot(v, basis.forward);
        float k = scale;
        if (perspective) {
            if (depth < near) return false;
            k = scale / depth;
        }
        sx = cx + x * k;
        sy = cy - y * k;
        samples_per_unit = k;
        return true;
    }
};

// Light directions in view coordinates (x right, y up, z into the picture).
const float3 kViewer{0.0f, 0.0f, -1.0f};
const float3 kKey = normalize(float3(-0.45f, 0.65f, -0.6f));  // from the upper left, in front

/// One colour attribute column resolved to spans.
struct ColorSource {
    std::span<const int32_t> i32;
    std::span<const int64_t> i64;
    std::span<const float> f32;
    bool per_point = false;
    bool valid() const { return !i32.empty() || !i64.empty() || !f32.empty(); }
    int64_t value(size_t i) const
    {
        if (!i32.empty()) return i32[i];
        if (!i64.empty()) return i64[i];
        return static_cast<int64_t>(std::floor(f32[i]));
    }
};

ColorSource find_color_source(const CurveSet& curves, std::string_view name)
{
    ColorSource s;
    for (Domain d : {Domain::Point, Domain::Curve}) {
        s.i32 = curves.find<int32_t>(d, name);
        s.i64 = curves.find<int64_t>(d, name);
        s.f32 = curves.find<float>(d, name);
        s.per_point = d == Domain::Point;
        if (s.valid()) return s;
    }
    return {};
}

std::string_view attribute_of(ColorBy c)
{
    switch (c) {
    case ColorBy::Strand: return "strand";
    case ColorBy::Guide: return "guide";
    case ColorBy::Shape: return "shape";
    case ColorBy::Kind: return "kind";
    default: return {};
    }
}

/// Everything drawn, projected for one camera. Points of all layers are concatenated.
struct Prepared {
    int ws = 0, hs = 0;  // sample grid
    // Curve points, one record each: a tile draws segments of curves scattered over the whole groom,
    // and one cache line per point instead of six (one per column) is what makes that fast.
    struct Point {
        float x, y, d;     // sample coordinates, depth
        float rad, wrad;   // radius in samples, in scene units
        uint32_t color;
    };
    std::vector<Point> pts;
    std::vector<uint32_t> segments;  // global index of each segment's first point
    float dmin = 0.0f, dmax = 0.0f;  // curve depth range, for the depth cue
    // mesh
    std::vector<float> vx, vy, vd;
    std::vector<float3> vn;  // view-space vertex normals
    std::vector<std::array<int32_t, 3>> tris;
    std::vector<uint8_t> vvalid;
};

/// Area-weighted vertex normals over the fan triangulation, so shared vertices shade smoothly.
std::vector<float3> vertex_normals(const PolygonSoup& mesh, std::vector<std::array<int32_t, 3>>& tris)
{
    std::vector<float3> n(mesh.points.size(), float3(0, 0, 0));
    for (size_t f = 0; f < mesh.num_faces(); ++f) {
        const auto face = mesh.face(f);
        for (size_t k = 1; k + 1 < face.size(); ++k) {
            const std::array<int32_t, 3> t{face[0], face[k], face[k + 1]};
            tris.push_back(t);
            const float3 fn = cross(mesh.points[t[1]] - mesh.points[t[0]], mesh.points[t[2]] - mesh.points[t[0]]);
            for (int32_t v : t) n[v] += fn;
        }
    }
    for (float3& v : n) v = normalize(v, float3(0, 0, 0));
    return n;
}

Prepared prepare(const RenderScene& scene, const Camera& cam, const RenderParams& params)
{
    Prepared p;
    const int S = params.supersample;
    p.ws = params.width * S;
    p.hs = params.height * S;
    const Projector proj(cam, p.ws, p.hs);
    const float nan = std::numeric_limits<float>::quiet_NaN();

    // ---- mesh
    if (scene.mesh) {
        const PolygonSoup& mesh = *scene.mesh;
        const std::vector<float3> normals = vertex_normals(mesh, p.tris);
        const size_t nv = mesh.points.size();
        p.vx.resize(nv);
        p.vy.resize(nv);
        p.vd.resize(nv);
        p.vn.resize(nv);
        p.vvalid.resize(nv);
        parallel_for(int64_t(nv), 4096, [&](int64_t b, int64_t e) {
            for (int64_t i = b; i < e; ++i) {
                float k = 0.0f;
                p.vvalid[i] = proj.project(mesh.points[i], p.vx[i], p.vy[i], p.vd[i], k) ? 1 : 0;
                const float3& n = normals[i];
                p.vn[i] = {dot(n, proj.basis.right), dot(n, proj.basis.up), dot(n, proj.basis.forward)};
            }
        });
    }

    // ---- curves
    size_t total = 0;
    for (const CurveSet* c : scene.curves) total += c->num_points();
    if (total >= std::numeric_limits<uint32_t>::max()) {
        throw LimitExceeded("render: " + std::to_string(total) + " curve points in all; at most 4294967294 can be drawn at once");
    }
    p.pts.resize(total);
    const float min_r = 0.5f * params.min_width_px * float(S);
    const float default_r = 0.5f * params.default_width_px * params.width_scale * float(S);
    size_t base = 0;
    for (size_t layer = 0; layer < scene.curves.size(); ++layer) {
        const CurveSet& curves = *scene.curves[layer];
        const auto P = curves.positions();
        const auto width = curves.find<float>(Domain::Point, attr::width);
        const uint32_t plain = pack(params.color);
        ColorSource source;
        std::vector<int64_t> ids;
        if (params.color_by == ColorBy::Id) ids = curves.curve_ids();
        else if (params.color_by != ColorBy::None && params.color_by != ColorBy::File) {
            source = find_color_source(curves, attribute_of(params.color_by));
        }
        const uint32_t file_color = pack(categorical_color(int64_t(layer)));
        parallel_for(int64_t(curves.num_curves()), 256, [&](int64_t cb, int64_t ce) {
            for (int64_t c = cb; c < ce; ++c) {
                const IndexRange r = curves.points_of(size_t(c));
                uint32_t curve_color = plain;
                if (params.color_by == ColorBy::Id) curve_color = pack(categorical_color(ids[c]));
                else if (params.color_by == ColorBy::File) curve_color = file_color;
                else if (source.valid() && !source.per_point) curve_color = pack(categorical_color(source.value(size_t(c))));
                for (int64_t i = r.begin; i < r.end; ++i) {
                    const size_t g = base + size_t(i);
                    float k = 0.0f;
                    Prepared::Point& q = p.pts[g];
                    if (!proj.project(P[i], q.x, q.y, q.d, k)) {
                        q.x = nan;
                        continue;
                    }
                    float rad = width.empty() ? default_r : 0.5f * width[i] * params.width_scale * k;
                    if (!(rad >= min_r)) rad = min_r;  // also catches NaN widths
                    q.rad = rad;
                    q.wrad = rad / k;
                    q.color = source.valid() && source.per_point ? pack(categorical_color(source.value(size_t(i)))) : curve_color;
                }
            }
        });
        for (size_t c = 0; c < curves.num_curves(); ++c) {
            const IndexRange r = curves.points_of(c);
            for (int64_t i = r.begin; i + 1 < r.end; ++i) p.segments.push_back(static_cast<uint32_t>(base + size_t(i)));
        }
        base += curves.num_points();
    }
    p.dmin = std::numeric_limits<float>::infinity();
    p.dmax = -p.dmin;
    for (size_t i = 0; i < total; ++i) {
        if (std::isnan(p.pts[i].x)) continue;
        p.dmin = std::min(p.dmin, p.pts[i].d);
        p.dmax = std::max(p.dmax, p.pts[i].d);
    }
    return p;
}

struct Rect {
    int x0, y0, x1, y1;  // half-open, samples
};

/// Sample index range [lo, hi] whose centres (i + 0.5) fall in [a, b], clipped to [clip0, clip1).
inline void sample_range(float a, float b, int clip0, int clip1, int& lo, int& hi)
{
    lo = std::max(clip0, static_cast<int>(std::ceil(a - 0.5f)));
    hi = std::min(clip1 - 1, static_cast<int>(std::floor(b - 0.5f)));
}

struct Buffers {
    int ws, hs;
    std::vector<float> depth;
    std::vector<uint32_t> color;
};

void draw_triangle(const Prepared& p, const std::array<int32_t, 3>& t, const Rect& tile, const RenderParams& params, Buffers& buf)
{
    const int a = t[0], b = t[1], c = t[2];
    const float ax = p.vx[a], ay = p.vy[a], bx = p.vx[b], by = p.vy[b], cx = p.vx[c], cy = p.vy[c];
    const float area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    if (!(std::fabs(area) > 1e-12f)) return;
    const float inv = 1.0f / area;
    int x0, x1, y0, y1;
    sample_range(std::min({ax, bx, cx}), std::max({ax, bx, cx}), tile.x0, tile.x1, x0, x1);
    sample_range(std::min({ay, by, cy}), std::max({ay, by, cy}), tile.y0, tile.y1, y0, y1);
    for (int y = y0; y <= y1; ++y) {
        const float sy = float(y) + 0.5f;
        for (int x = x0; x <= x1; ++x) {
            const float sx = float(x) + 0.5f;
            // Barycentric weights from edge functions; the sign of `area` cancels, so either winding draws.
            const float w0 = ((bx - sx) * (cy - sy) - (by - sy) * (cx - sx)) * inv;
            const float w1 = ((cx - sx) * (ay - sy) - (cy - sy) * (ax - sx)) * inv;
            const float w2 = 1.0f - w0 - w1;
            if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) continue;
            const float d = w0 * p.vd[a] + w1 * p.vd[b] + w2 * p.vd[c];
            const size_t idx = size_t(y) * size_t(buf.ws) + size_t(x);
            if (!(d < buf.depth[idx])) continue;
            float3 n = normalize(p.vn[a] * w0 + p.vn[b] * w1 + p.vn[c] * w2, float3(0, 0, -1));
            if (n.z > 0.0f) n = -n;  // two-sided: inside-out or inconsistently wound meshes still shade
            const float diffuse = std::max(0.0f, dot(n, kViewer));
            const float key = std::max(0.0f, dot(n, kKey));
            buf.depth[idx] = d;
            buf.color[idx] = pack(params.scalp_color * (0.18f + 0.55f * diffuse + 0.40f * key));
        }
    }
}

void draw_segment(const Prepared& p, uint32_t i, const Rect& tile, Buffers& buf)
{
    const Prepared::Point& A = p.pts[i];
    const Prepared::Point& B = p.pts[i + 1];
    const float ax = A.x, ay = A.y, bx = B.x, by = B.y;
    const float r0 = A.rad, r1 = B.rad;
    const float rmax = std::max(r0, r1);
    int x0, x1, y0, y1;
    sample_range(std::min(ax, bx) - rmax, std::max(ax, bx) + rmax, tile.x0, tile.x1, x0, x1);
    sample_range(std::min(ay, by) - rmax, std::max(ay, by) + rmax, tile.y0, tile.y1, y0, y1);
    if (x0 > x1 || y0 > y1) return;
    const float ex = bx - ax, ey = by - ay;
    const float len2 = ex * ex + ey * ey;
    const float inv_len2 = len2 > 1e-12f ? 1.0f / len2 : 0.0f;
    // View-space tangent (scene units) for the hair highlight (Kajiya-Kay): a strand lights up where
    // its tangent is perpendicular to the half vector, so crossings in a braid catch the light differently.
    const float k = A.rad / std::max(A.wrad, 1e-30f);  // samples per scene unit here
    const float3 tangent = normalize(float3(ex / k, -ey / k, B.d - A.d), float3(1, 0, 0));
    const float3 half = normalize(kKey + kViewer);
    const float th = dot(tangent, half);
    const float sin_th = std::sqrt(std::max(0.0f, 1.0f - th * th));
    const float spec = 0.30f * std::pow(sin_th, 40.0f);
    const float tl = dot(tangent, kKey);
    const float kay_diffuse = std::sqrt(std::max(0.0f, 1.0f - tl * tl));
    const float drange = p.dmax - p.dmin;
    // Per row, only the samples within the band |x - x_line(y)| <= r len / |ey| can be within r of
    // the segment (the capsule lies inside that band): a long diagonal segment then costs its area,
    // not its bounding box's.
    const float len = std::sqrt(len2);
    const bool steep = std::fabs(ey) > 1e-6f;
    const float slope = steep ? ex / ey : 0.0f;
    const float half_band = steep ? rmax * len / std::fabs(ey) : 0.0f;
    // Everything that does not vary per sample, hoisted out of the loop.
    const float d0 = A.d, dd = B.d - A.d;
    const float rw0 = A.wrad, drw = B.wrad - A.wrad;
    const float dr = r1 - r0;
    const float cue_scale = drange > 0.0f ? 0.35f / drange : 0.0f;
    const float3 base0 = unpack(A.color), base1 = unpack(B.color);
    const float light0 = 0.30f + 0.30f * kay_diffuse;
    for (int y = y0; y <= y1; ++y) {
        const float sy = float(y) + 0.5f;
        int xa = x0, xb = x1;
        if (steep) {
            const float xc = ax + (sy - ay) * slope;
            xa = std::max(x0, static_cast<int>(std::ceil(xc - half_band - 0.5f)));
            xb = std::min(x1, static_cast<int>(std::floor(xc + half_band - 0.5f)));
        }
        const float dy = sy - ay;
        float* depth_row = buf.depth.data() + size_t(y) * size_t(buf.ws);
        uint32_t* color_row = buf.color.data() + size_t(y) * size_t(buf.ws);
        for (int x = xa; x <= xb; ++x) {
            const float dx = float(x) + 0.5f - ax;
            const float t = std::clamp((dx * ex + dy * ey) * inv_len2, 0.0f, 1.0f);
            const float qx = dx - t * ex, qy = dy - t * ey;
            const float dist2 = qx * qx + qy * qy;
            const float r = r0 + dr * t;
            const float r2 = r * r;
            if (dist2 > r2) continue;
            // A tube: its front surface is nearer than the centreline by the radius times cos(angle),
            // so curves lying on the scalp win the depth test and braided strands occlude correctly.
            const float centre_depth = d0 + dd * t;
            const float rw = rw0 + drw * t;
            // Hidden even at the tube's nearest point: most samples of a dense groom end here.
            if (!(centre_depth - rw < depth_row[x])) continue;
            const float cosv = std::sqrt(std::max(0.0f, 1.0f - dist2 / r2));
            const float d = centre_depth - rw * cosv;
            if (!(d < depth_row[x])) continue;
            const float cue = 1.0f - cue_scale * (centre_depth - p.dmin);
            const float light = (light0 + 0.50f * cosv) * cue;
            const float s = spec * cosv;
            depth_row[x] = d;
            color_row[x] = pack((t < 0.5f ? base0 : base1) * light + float3(s, s, s));
        }
    }
}

float3 hsv(float h, float s, float v)
{
    h = (h - std::floor(h)) * 6.0f;
    const int i = static_cast<int>(h) % 6;
    const float f = h - std::floor(h);
    const float a = v * (1 - s), b = v * (1 - s * f), c = v * (1 - s * (1 - f));
    switch (i) {
    case 0: return {v, c, a};
    case 1: return {b, v, a};
    case 2: return {a, v, c};
    case 3: return {a, b, v};
    case 4: return {c, a, v};
    default: return {v, a, b};
    }
}

// 5x7 glyphs, one row per byte, bit 4 = leftmost column.
struct Glyph {
    char c;
    uint8_t rows[7];
};
constexpr Glyph kFont[] = {
    {'A', {14, 17, 17, 31, 17, 17, 17}}, {'B', {30, 17, 17, 30, 17, 17, 30}}, {'C', {14, 17, 16, 16, 16, 17, 14}},
    {'D', {30, 17, 17, 17, 17, 17, 30}}, {'E', {31, 16, 16, 30, 16, 16, 31}}, {'F', {31, 16, 16, 30, 16, 16, 16}},
    {'G', {14, 17, 16, 23, 17, 17, 15}}, {'H', {17, 17, 17, 31, 17, 17, 17}}, {'I', {14, 4, 4, 4, 4, 4, 14}},
    {'J', {7, 2, 2, 2, 2, 18, 12}},      {'K', {17, 18, 20, 24, 20, 18, 17}}, {'L', {16, 16, 16, 16, 16, 16, 31}},
    {'M', {17, 27, 21, 21, 17, 17, 17}}, {'N', {17, 17, 25, 21, 19, 17, 17}}, {'O', {14, 17, 17, 17, 17, 17, 14}},
    {'P', {30, 17, 17, 30, 16, 16, 16}}, {'Q', {14, 17, 17, 17, 21, 18, 13}}, {'R', {30, 17, 17, 30, 20, 18, 17}},
    {'S', {15, 16, 16, 14, 1, 1, 30}},   {'T', {31, 4, 4, 4, 4, 4, 4}},       {'U', {17, 17, 17, 17, 17, 17, 14}},
    {'V', {17, 17, 17, 17, 17, 10, 4}},  {'W', {17, 17, 17, 21, 21, 21, 10}}, {'X', {17, 17, 10, 4, 10, 17, 17}},
    {'Y', {17, 17, 10, 4, 4, 4, 4}},     {'Z', {31, 1, 2, 4, 8, 16, 31}},     {'0', {14, 17, 19, 21, 25, 17, 14}},
    {'1', {4, 12, 4, 4, 4, 4, 14}},      {'2', {14, 17, 1, 2, 4, 8, 31}},     {'3', {31, 2, 4, 2, 1, 17, 14}},
    {'4', {2, 6, 10, 18, 31, 2, 2}},     {'5', {31, 16, 30, 1, 1, 17, 14}},   {'6', {6, 8, 16, 30, 17, 17, 14}},
    {'7', {31, 1, 2, 4, 8, 8, 8}},       {'8', {14, 17, 17, 14, 17, 17, 14}}, {'9', {14, 17, 17, 15, 1, 2, 12}},
    {'-', {0, 0, 0, 31, 0, 0, 0}},       {'.', {0, 0, 0, 0, 0, 12, 12}},      {':', {0, 12, 12, 0, 12, 12, 0}},
    {',', {0, 0, 0, 0, 12, 4, 8}},       {'/', {1, 1, 2, 4, 8, 16, 16}},      {' ', {0, 0, 0, 0, 0, 0, 0}},
};

const Glyph* find_glyph(char c)
{
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    for (const Glyph& g : kFont)
        if (g.c == c) return &g;
    return nullptr;
}

}  // namespace

View parse_view(std::string_view name)
{
    if (name == "front") return View::Front;
    if (name == "back") return View::Back;
    if (name == "left" || name == "side") return View::Left;
    if (name == "right") return View::Right;
    if (name == "top") return View::Top;
    if (name == "three-quarter" || name == "threequarter" || name == "3/4") return View::ThreeQuarter;
    throw InvalidParam("render: unknown view '" + std::string(name) + "' (expected front, back, left, right, top or three-quarter)");
}

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
        throw InvalidParam("render: --camera values must be finite (got eye " + fmt(eye.x) + "," + fmt(eye.y) + "," + fmt(eye.z) +
                           ", target " + fmt(target.x) + "," + fmt(target.y) + "," + fmt(target.z) + ")");
    }
    const float size = std::max({1.0f, length(eye), length(target)});
    if (distance(eye, target) <= 1e-6f * size) {
        throw InvalidParam("render: --camera eye and target must differ (both are " + fmt(eye.x) + "," + fmt(eye.y) + "," +
                           fmt(eye.z) + ")");
    }
    if (length(up) == 0.0f) throw InvalidParam("render: camera up vector must not be zero");
    if (!std::isfinite(fov_degrees) || fov_degrees < 0.0f || fov_degrees >= 170.0f) {
        throw InvalidParam("render: --fov must be in (0, 170) degrees, or 0 for orthographic (got " + fmt(fov_degrees) + ")");
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

ColorBy parse_color_by(std::string_view name)
{
    if (name == "none") return ColorBy::None;
    if (name == "strand") return ColorBy::Strand;
    if (name == "guide") return ColorBy::Guide;
    if (name == "shape") return ColorBy::Shape;
    if (name == "kind") return ColorBy::Kind;
    if (name == "id") return ColorBy::Id;
    if (name == "file") return ColorBy::File;
    throw InvalidParam("render: unknown --color-by '" + std::string(name) + "' (expected none, strand, guide, shape, kind, id or file)");
}

std::string_view color_by_name(ColorBy c)
{
    switch (c) {
    case ColorBy::None: return "none";
    case ColorBy::Strand: return "strand";
    case ColorBy::Guide: return "guide";
    case ColorBy::Shape: return "shape";
    case ColorBy::Kind: return "kind";
    case ColorBy::Id: return "id";
    case ColorBy::File: return "file";
    }
    return "none";
}

float3 categorical_color(int64_t value)
{
    // Golden-ratio hue steps (computed in double so large ids stay exact enough), alternating two
    // brightness levels so even hues that come close again differ in value.
    const double h = 0.08 + 0.6180339887498949 * static_cast<double>(value);
    const float hue = static_cast<float>(h - std::floor(h));
    const bool odd = (value & 1) != 0;
    return hsv(hue, odd ? 0.55f : 0.70f, odd ? 0.95f : 0.82f);
}

void RenderParams::validate() const
{
    if (width < 1 || height < 1) {
        throw InvalidParam("render: --size must be at least 1x1 pixels (got " + std::to_string(width) + "x" + std::to_string(height) + ")");
    }
    if (width > kMaxSide || height > kMaxSide) {
        throw InvalidParam("render: --size must be at most " + std::to_string(kMaxSide) + " pixels per side (got " +
                           std::to_string(width) + "x" + std::to_string(height) + ")");
    }
    if (supersample < 1 || supersample > 4) {
        throw InvalidParam("render: --supersample must be in [1, 4] (got " + std::to_string(supersample) + ")");
    }
    const int64_t samples = int64_t(width) * height * supersample * supersample;
    if (samples > kMaxSamples) {
        throw InvalidParam("render: --size " + std::to_string(width) + "x" + std::to_string(height) + " with --supersample " +
                           std::to_string(supersample) + " needs " + std::to_string(samples) + " samples, more than the " +
                           std::to_string(kMaxSamples) + " allowed; lower --size or --supersample");
    }
    check_color("--color", color);
    check_color("--scalp-color", scalp_color);
    check_color("--background", background);
    if (!std::isfinite(width_scale) || width_scale <= 0.0f) {
        throw InvalidParam("render: --width-scale must be > 0 (got " + fmt(width_scale) + ")");
    }
    if (!std::isfinite(min_width_px) || min_width_px < 0.25f || min_width_px > 64.0f) {
        throw InvalidParam("render: --min-width must be in [0.25, 64] pixels (got " + fmt(min_width_px) + ")");
    }
    if (!std::isfinite(default_width_px) || default_width_px <= 0.0f || default_width_px > 256.0f) {
        throw InvalidParam("render: --line-width must be in (0, 256] pixels (got " + fmt(default_width_px) + ")");
    }
    if (!std::isfinite(margin) || margin < 0.0f || margin > 0.45f) {
        throw InvalidParam("render: --margin must be in [0, 0.45] (got " + fmt(margin) + ")");
    }
}

bool has_color_attribute(const CurveSet& curves, ColorBy color_by)
{
    const std::string_view name = attribute_of(color_by);
    return name.empty() || find_color_source(curves, name).valid();
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

RgbImage render(const RenderScene& scene, const Camera& camera_in, const RenderParams& params, Progress* progress)
{
    params.validate();
    const Camera camera = frame_camera(scene, camera_in, float(params.width) / float(params.height), params.margin);
    const Prepared p = prepare(scene, camera, params);

    // ---- bin triangles and segments into tiles: count, prefix sum, fill (input order kept per tile)
    const int tiles_x = (p.ws + kTile - 1) / kTile, tiles_y = (p.hs + kTile - 1) / kTile;
    const size_t num_tiles = size_t(tiles_x) * size_t(tiles_y);
    const size_t num_tris = p.tris.size();
    const size_t num_items = num_tris + p.segments.size();
    auto item_tiles = [&](size_t item, int& tx0, int& tx1, int& ty0, int& ty1) -> bool {
        float xlo, xhi, ylo, yhi;
        if (item < num_tris) {
            const auto& t = p.tris[item];
            if (!p.vvalid[t[0]] || !p.vvalid[t[1]] || !p.vvalid[t[2]]) return false;
            xlo = std::min({p.vx[t[0]], p.vx[t[1]], p.vx[t[2]]});
            xhi = std::max({p.vx[t[0]], p.vx[t[1]], p.vx[t[2]]});
            ylo = std::min({p.vy[t[0]], p.vy[t[1]], p.vy[t[2]]});
            yhi = std::max({p.vy[t[0]], p.vy[t[1]], p.vy[t[2]]});
        }
        else {
            const uint32_t i = p.segments[item - num_tris];
            const Prepared::Point& A = p.pts[i];
            const Prepared::Point& B = p.pts[i + 1];
            if (std::isnan(A.x) || std::isnan(B.x)) return false;
            const float r = std::max(A.rad, B.rad);
            xlo = std::min(A.x, B.x) - r;
            xhi = std::max(A.x, B.x) + r;
            ylo = std::min(A.y, B.y) - r;
            yhi = std::max(A.y, B.y) + r;
        }
        if (!(xhi >= 0.0f && yhi >= 0.0f && xlo < float(p.ws) && ylo < float(p.hs))) return false;
        tx0 = std::max(0, int(xlo) / kTile);
        tx1 = std::min(tiles_x - 1, int(std::min(xhi, float(p.ws - 1))) / kTile);
        ty0 = std::max(0, int(ylo) / kTile);
        ty1 = std::min(tiles_y - 1, int(std::min(yhi, float(p.hs - 1))) / kTile);
        return true;
    };
    std::vector<uint64_t> tile_offsets(num_tiles + 1, 0);
    for (size_t item = 0; item < num_items; ++item) {
        int tx0, tx1, ty0, ty1;
        if (!item_tiles(item, tx0, tx1, ty0, ty1)) continue;
        for (int ty = ty0; ty <= ty1; ++ty)
            for (int tx = tx0; tx <= tx1; ++tx) ++tile_offsets[size_t(ty) * tiles_x + tx + 1];
    }
    for (size_t t = 0; t < num_tiles; ++t) tile_offsets[t + 1] += tile_offsets[t];
    // Each entry is what the draw needs without another lookup: a triangle index with the top bit set,
    // or a segment's first point index.
    constexpr uint64_t kTriangleBit = uint64_t(1) << 63;
    std::vector<uint64_t> tile_items(tile_offsets.back());
    {
        std::vector<uint64_t> cursor(tile_offsets.begin(), tile_offsets.end() - 1);
        for (size_t item = 0; item < num_items; ++item) {
            int tx0, tx1, ty0, ty1;
            if (!item_tiles(item, tx0, tx1, ty0, ty1)) continue;
            const uint64_t entry = item < num_tris ? (uint64_t(item) | kTriangleBit) : uint64_t(p.segments[item - num_tris]);
            for (int ty = ty0; ty <= ty1; ++ty)
                for (int tx = tx0; tx <= tx1; ++tx) tile_items[cursor[size_t(ty) * tiles_x + tx]++] = entry;
        }
    }

    // ---- draw tiles in parallel: each task owns its tile's samples
    Buffers buf{p.ws, p.hs, {}, {}};
    buf.depth.assign(size_t(p.ws) * size_t(p.hs), std::numeric_limits<float>::infinity());
    buf.color.assign(buf.depth.size(), pack(params.background));
    ProgressStep step(progress, "render", int64_t(num_tiles));
    parallel_for(int64_t(num_tiles), 1, [&](int64_t tb, int64_t te) {
        for (int64_t t = tb; t < te; ++t) {
            const int tx = int(t % tiles_x), ty = int(t / tiles_x);
            const Rect rect{tx * kTile, ty * kTile, std::min(p.ws, (tx + 1) * kTile), std::min(p.hs, (ty + 1) * kTile)};
            const uint64_t end = tile_offsets[t + 1];
            for (uint64_t k = tile_offsets[t]; k < end; ++k) {
                // Segments of a tile come from curves all over the groom: fetch the point records a
                // few items ahead so the memory latency overlaps the drawing.
                if (k + 8 < end && !(tile_items[k + 8] & kTriangleBit)) __builtin_prefetch(&p.pts[tile_items[k + 8]]);
                const uint64_t entry = tile_items[k];
                if (entry & kTriangleBit) draw_triangle(p, p.tris[entry & ~kTriangleBit], rect, params, buf);
                else draw_segment(p, static_cast<uint32_t>(entry), rect, buf);
            }
            step.advance(1);
        }
    });

    // ---- box-filter S x S samples down to one pixel
    const int S = params.supersample;
    RgbImage image(params.width, params.height);
    parallel_for(params.height, 16, [&](int64_t yb, int64_t ye) {
        for (int64_t y = yb; y < ye; ++y) {
            for (int x = 0; x < params.width; ++x) {
                uint32_t sum[3] = {0, 0, 0};
                for (int sy = 0; sy < S; ++sy) {
                    const uint32_t* row = buf.color.data() + (size_t(y) * S + sy) * size_t(p.ws) + size_t(x) * S;
                    for (int sx = 0; sx < S; ++sx) {
                        sum[0] += row[sx] & 255u;
                        sum[1] += (row[sx] >> 8) & 255u;
                        sum[2] += (row[sx] >> 16) & 255u;
                    }
                }
                uint8_t* out = image.at(x, int(y));
                const uint32_t n = uint32_t(S * S);
                for (int c = 0; c < 3; ++c) out[c] = static_cast<uint8_t>((sum[c] + n / 2) / n);
            }
        }
    });
    return image;
}

void draw_label(RgbImage& image, int x, int y, std::string_view text, int scale, const float3& color)
{
    const uint8_t rgb[3] = {static_cast<uint8_t>(pack(color) & 255u), static_cast<uint8_t>((pack(color) >> 8) & 255u),
                            static_cast<uint8_t>((pack(color) >> 16) & 255u)};
    scale = std::max(1, scale);
    int pen = x;
    for (char ch : text) {
        const Glyph* g = find_glyph(ch);
        if (g) {
            for (int row = 0; row < 7; ++row)
                for (int col = 0; col < 5; ++col) {
                    if (!(g->rows[row] & (16 >> col))) continue;
                    for (int dy = 0; dy < scale; ++dy)
                        for (int dx = 0; dx < scale; ++dx) {
                            const int px = pen + col * scale + dx, py = y + row * scale + dy;
                            if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
                            std::memcpy(image.at(px, py), rgb, 3);
                        }
                }
        }
        pen += 6 * scale;
    }
}

RgbImage render_sheet(const RenderScene& scene, std::span<const View> views, const RenderParams& params, Progress* progress)
{
    if (views.empty()) throw InvalidParam("render: --views needs at least one view");
    params.validate();
    if (int64_t(params.width) * int64_t(views.size()) > kMaxSide) {
        throw InvalidParam("render: a sheet of " + std::to_string(views.size()) + " views of width " + std::to_string(params.width) +
                           " is wider than " + std::to_string(kMaxSide) + " pixels; lower --size");
    }
    const float aspect = float(params.width) / float(params.height);
    // One scale for every view, so sizes compare across the sheet.
    std::vector<Camera> cams;
    float height = 0.0f;
    for (View v : views) {
        cams.push_back(frame_camera(scene, view_camera(v), aspect, params.margin));
        height = std::max(height, cams.back().ortho_height);
    }
    RgbImage sheet(params.width * int(views.size()), params.height);
    const int scale = std::max(2, params.height / 200);
    for (size_t i = 0; i < views.size(); ++i) {
        cams[i].ortho_height = height;
        RgbImage one = render(scene, cams[i], params, progress);
        draw_label(one, 4 * scale, 4 * scale, view_name(views[i]), scale, float3(0.25f, 0.25f, 0.28f));
        for (int y = 0; y < params.height; ++y) {
            std::memcpy(sheet.at(int(i) * params.width, y), one.at(0, y), size_t(params.width) * 3u);
            if (i > 0) std::memset(sheet.at(int(i) * params.width, y), 200, 3);  // a thin divider
        }
    }
    return sheet;
}

}  // namespace groom
