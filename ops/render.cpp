// The rasteriser behind render(): the scene projected to a sample grid, triangles and tube segments
// binned into tiles and drawn through one z-buffer, then box-filtered to pixels. Cameras, colours, the
// font and the contact sheet are in render_camera/color/font/sheet.cpp; render_impl.h holds what they share.
#include "kernel/parallel.h"
#include "ops/render_impl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace groom {

using namespace render_detail;

namespace {

constexpr int kTile = 32;                       // tile side in samples: a few KB of z-buffer per task
constexpr int64_t kMaxSamples = int64_t(1) << 27;  // 128 M samples = 1 GiB of colour + depth

void check_color(const char* option, const float3& c)
{
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(c[i]) || c[i] < 0.0f || c[i] > 1.0f) {
            throw InvalidParam(std::string("render: ") + option + " components must be in [0, 1] (got " + fmt(c.x) + "," +
                               fmt(c.y) + "," + fmt(c.z) + ")");
        }
    }
}

// Light directions in view coordinates (x right, y up, z into the picture).
const float3 kViewer{0.0f, 0.0f, -1.0f};
const float3 kKey = normalize(float3(-0.45f, 0.65f, -0.6f));  // from the upper left, in front

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
    // Turned outward where the winding runs inward throughout (the ponytail head's is left-handed):
    // the signed volume, positive for an outward closed surface, tells which way it runs, and the
    // normals' sign which side of the surface a sample shows (draw_segment). Shading is two-sided
    // and does not change.
    double volume = 0.0;
    for (const auto& t : tris) volume += double(dot(mesh.points[t[0]], cross(mesh.points[t[1]], mesh.points[t[2]])));
    const float sign = volume < 0.0 ? -1.0f : 1.0f;
    for (float3& v : n) v = normalize(v, float3(0, 0, 0)) * sign;
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

/// v clipped to [lo, hi] in float, then converted: a point of width 1e30 puts sample coordinates far
/// past int's range, where converting is undefined (found by the op fuzzer). NaN gives lo.
inline int clipped_int(float v, int lo, int hi) { return static_cast<int>(std::fmin(std::fmax(v, float(lo)), float(hi))); }

/// Sample index range [lo, hi] whose centres (i + 0.5) fall in [a, b], clipped to [clip0, clip1)
/// (empty, lo > hi, when none does).
inline void sample_range(float a, float b, int clip0, int clip1, int& lo, int& hi)
{
    lo = clipped_int(std::ceil(a - 0.5f), clip0, clip1);
    hi = clipped_int(std::floor(b - 0.5f), clip0 - 1, clip1 - 1);
}

struct Buffers {
    int ws, hs;
    std::vector<float> depth;
    std::vector<uint32_t> color;
    /// 1 where the sample shows the inside of the scalp (its far wall through an eye hole or a neck
    /// cut): hair must be in front of it by its centreline, not by its tube (draw_segment).
    std::vector<uint8_t> inner;
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
            const bool inner = n.z > 0.0f;  // facing away from the viewer: the surface's inside
            if (inner) n = -n;  // two-sided: inside-out or inconsistently wound meshes still shade
            const float diffuse = std::max(0.0f, dot(n, kViewer));
            const float key = std::max(0.0f, dot(n, kKey));
            buf.depth[idx] = d;
            buf.inner[idx] = inner ? 1 : 0;
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
            xa = clipped_int(std::ceil(xc - half_band - 0.5f), x0, x1 + 1);
            xb = clipped_int(std::floor(xc + half_band - 0.5f), x0 - 1, x1);
        }
        const float dy = sy - ay;
        float* depth_row = buf.depth.data() + size_t(y) * size_t(buf.ws);
        uint32_t* color_row = buf.color.data() + size_t(y) * size_t(buf.ws);
        uint8_t* inner_row = buf.inner.data() + size_t(y) * size_t(buf.ws);
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
            // The tube's near side lets hair lying on the scalp win over it. Seen from inside the
            // head, hair lying just outside its far wall won the same way and filled the eye holes
            // of Sintel's open bust with the gathered hair behind (a trial): there the centreline
            // must be in front.
            if (inner_row[x] && !(centre_depth < depth_row[x])) continue;
            const float cue = 1.0f - cue_scale * (centre_depth - p.dmin);
            const float light = (light0 + 0.50f * cosv) * cue;
            const float s = spec * cosv;
            depth_row[x] = d;
            inner_row[x] = 0;
            color_row[x] = pack((t < 0.5f ? base0 : base1) * light + float3(s, s, s));
        }
    }
}

}  // namespace

void RenderParams::validate() const
{
    if (width < 1 || height < 1) {
        throw InvalidParam("render: `size` must be at least 1x1 pixels (got " + std::to_string(width) + "x" + std::to_string(height) + ")");
    }
    if (width > kMaxSide || height > kMaxSide) {
        throw InvalidParam("render: `size` must be at most " + std::to_string(kMaxSide) + " pixels per side (got " +
                           std::to_string(width) + "x" + std::to_string(height) + ")");
    }
    if (supersample < 1 || supersample > 4) {
        throw InvalidParam("render: `supersample` must be in [1, 4] (got " + std::to_string(supersample) + ")");
    }
    const int64_t samples = int64_t(width) * height * supersample * supersample;
    if (samples > kMaxSamples) {
        throw InvalidParam("render: `size` " + std::to_string(width) + "x" + std::to_string(height) + " with `supersample` " +
                           std::to_string(supersample) + " needs " + std::to_string(samples) + " samples, more than the " +
                           std::to_string(kMaxSamples) + " allowed; lower `size` or `supersample`");
    }
    check_color("`color`", color);
    check_color("`scalp_color`", scalp_color);
    check_color("`background`", background);
    if (!std::isfinite(width_scale) || width_scale <= 0.0f) {
        throw InvalidParam("render: `width_scale` must be > 0 (got " + fmt(width_scale) + ")");
    }
    if (!std::isfinite(min_width_px) || min_width_px < 0.25f || min_width_px > 64.0f) {
        throw InvalidParam("render: `min_width` must be in [0.25, 64] pixels (got " + fmt(min_width_px) + ")");
    }
    if (!std::isfinite(default_width_px) || default_width_px <= 0.0f || default_width_px > 256.0f) {
        throw InvalidParam("render: `line_width` must be in (0, 256] pixels (got " + fmt(default_width_px) + ")");
    }
    if (!std::isfinite(margin) || margin < 0.0f || margin > 0.45f) {
        throw InvalidParam("render: `margin` must be in [0, 0.45] (got " + fmt(margin) + ")");
    }
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
        tx0 = clipped_int(xlo, 0, p.ws - 1) / kTile;
        tx1 = std::min(tiles_x - 1, clipped_int(xhi, 0, p.ws - 1) / kTile);
        ty0 = clipped_int(ylo, 0, p.hs - 1) / kTile;
        ty1 = std::min(tiles_y - 1, clipped_int(yhi, 0, p.hs - 1) / kTile);
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
    buf.inner.assign(buf.depth.size(), 0);
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

}  // namespace groom
