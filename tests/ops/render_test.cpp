#include "ops/render.h"

#include "kernel/error.h"
#include "kernel/parallel.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace groom;

namespace {

/// A closed UV sphere as quads and pole triangles.
PolygonSoup uv_sphere(const float3& c, float r, int nlat = 48, int nlon = 96)
{
    PolygonSoup s;
    s.points.push_back(c + float3(0, r, 0));
    for (int i = 1; i < nlat; ++i)
        for (int k = 0; k < nlon; ++k) {
            const float th = 3.14159265f * float(i) / float(nlat), ph = 6.2831853f * float(k) / float(nlon);
            s.points.push_back(c + float3(std::sin(th) * std::sin(ph), std::cos(th), std::sin(th) * std::cos(ph)) * r);
        }
    s.points.push_back(c - float3(0, r, 0));
    auto v = [&](int i, int k) { return int32_t(1 + (i - 1) * nlon + k % nlon); };
    for (int k = 0; k < nlon; ++k) {
        const int32_t t[3] = {0, v(1, k), v(1, k + 1)};
        s.add_face(t);
    }
    for (int i = 1; i < nlat - 1; ++i)
        for (int k = 0; k < nlon; ++k) {
            const int32_t q[4] = {v(i, k), v(i + 1, k), v(i + 1, k + 1), v(i, k + 1)};
            s.add_face(q);
        }
    const int32_t last = int32_t(s.points.size() - 1);
    for (int k = 0; k < nlon; ++k) {
        const int32_t t[3] = {last, v(nlat - 1, k + 1), v(nlat - 1, k)};
        s.add_face(t);
    }
    return s;
}

CurveSet polyline(std::initializer_list<float3> pts)
{
    const int64_t n = int64_t(pts.size());
    CurveSet c = CurveSet::from_counts(std::span<const int64_t>(&n, 1));
    std::copy(pts.begin(), pts.end(), c.positions_for_write().begin());
    return c;
}

bool is_background(const RgbImage& im, int x, int y, const RenderParams& p)
{
    const uint8_t* px = im.at(x, y);
    for (int c = 0; c < 3; ++c)
        if (px[c] != static_cast<uint8_t>(p.background[c] * 255.0f + 0.5f)) return false;
    return true;
}

/// "Red" = the curve colour used below, as opposed to the grey sphere and white background.
bool is_red(const uint8_t* px) { return px[0] > px[1] + 60 && px[0] > px[2] + 60; }

int count_red(const RgbImage& im)
{
    int n = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) n += is_red(im.at(x, y)) ? 1 : 0;
    return n;
}

/// Orthographic front camera: 10 scene units over 100 pixels, so 0.1 units per pixel and the origin
/// at the corner shared by pixels (49, 49) and (50, 50).
Camera front_ortho()
{
    Camera cam;
    cam.eye = {0, 0, 10};
    cam.target = {0, 0, 0};
    cam.ortho_height = 10.0f;
    return cam;
}

RenderParams small_params()
{
    RenderParams p;
    p.width = p.height = 100;
    p.background = {1, 1, 1};
    p.color = {0.9f, 0.05f, 0.05f};
    p.scalp_color = {0.5f, 0.5f, 0.5f};
    p.default_width_px = 1.0f;
    p.min_width_px = 1.0f;
    return p;
}

}  // namespace

TEST(Render, HorizontalCurveLandsOnItsRowAndColumns)
{
    // y = 1.05 is the centre of pixel row 39 (rows 0..99 span y = 5 .. -5 downwards); x from -2 to 2
    // covers columns 30..69 exactly. A 1-pixel-wide line must fill that row and touch no other row,
    // and leave columns < 29 and > 70 untouched (29 and 70 hold the round caps' half pixels).
    const CurveSet c = polyline({{-2.0f, 1.05f, 0.0f}, {0.0f, 1.05f, 0.0f}, {2.0f, 1.05f, 0.0f}});
    RenderScene scene;
    scene.curves = {&c};
    const RenderParams p = small_params();
    const RgbImage im = render(scene, front_ortho(), p);
    ASSERT_EQ(im.width, 100);
    ASSERT_EQ(im.height, 100);
    for (int x = 30; x <= 69; ++x) {
        EXPECT_TRUE(is_red(im.at(x, 39))) << "column " << x;
        EXPECT_TRUE(is_background(im, x, 38, p)) << "column " << x;
        EXPECT_TRUE(is_background(im, x, 40, p)) << "column " << x;
    }
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 100; ++x) {
            const bool inside = y == 39 && x >= 29 && x <= 70;
            if (!inside) EXPECT_TRUE(is_background(im, x, y, p)) << x << "," << y;
        }
}

TEST(Render, VerticalCurveInPerspectiveLandsOnCentreColumn)
{
    // A curve through the target, parallel to the picture's up axis, projects onto the centre
    // column pair whatever the field of view; its length in pixels follows the pinhole formula.
    const CurveSet c = polyline({{0.05f * 0.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}});
    RenderScene scene;
    scene.curves = {&c};
    RenderParams p = small_params();
    p.width = 101;  // odd: the centre column is pixel 50
    p.height = 101;
    Camera cam;
    cam.eye = {0, 0, 10};
    cam.fov_degrees = 30.0f;
    const RgbImage im = render(scene, cam, p);
    // Half-height in pixels = (1 / 10) / tan(15 deg) * 50.5.
    const float half = 0.1f / std::tan(15.0f * 3.14159265f / 180.0f) * 50.5f;
    const int top = int(std::ceil(50.5f - half)), bottom = int(std::floor(50.5f + half)) - 1;
    for (int y = top + 1; y < bottom; ++y) {
        EXPECT_TRUE(is_red(im.at(50, y))) << "row " << y;
        EXPECT_TRUE(is_background(im, 48, y, p));
        EXPECT_TRUE(is_background(im, 52, y, p));
    }
    EXPECT_TRUE(is_background(im, 50, top - 2, p));
    EXPECT_TRUE(is_background(im, 50, bottom + 2, p));
}

TEST(Render, HeadHidesCurveBehindItAndShowsCurveInFront)
{
    const PolygonSoup sphere = uv_sphere({0, 0, 0}, 1.0f);
    const CurveSet behind = polyline({{-0.5f, 0.0f, -2.0f}, {0.5f, 0.0f, -2.0f}});
    const CurveSet in_front = polyline({{-0.5f, 0.3f, 2.0f}, {0.5f, 0.3f, 2.0f}});
    RenderParams p = small_params();
    p.default_width_px = 3.0f;

    RenderScene hidden;
    hidden.mesh = &sphere;
    hidden.curves = {&behind};
    Camera front = front_ortho();
    front.ortho_height = 3.0f;
    EXPECT_EQ(count_red(render(hidden, front, p)), 0) << "the sphere must hide a curve behind it";

    Camera back = front;
    back.eye = {0, 0, -10};
    EXPECT_GT(count_red(render(hidden, back, p)), 50) << "seen from behind, the same curve is in front";

    RenderScene visible;
    visible.mesh = &sphere;
    visible.curves = {&in_front};
    EXPECT_GT(count_red(render(visible, front, p)), 50);

    // The sphere itself is drawn: its centre pixel is grey, shaded, not background.
    const RgbImage im = render(hidden, front, p);
    EXPECT_FALSE(is_background(im, 50, 50, p));
    EXPECT_FALSE(is_red(im.at(50, 50)));
}

// Through a hole in the scalp (an eye hole, a neck cut) the camera sees the inside of the far wall.
// A hair lying just outside that wall, nearer to it than its own radius, is behind it: hidden, not
// drawn over it by the tube's near side that lets hair lying on the scalp win over the scalp (the
// gathered hair at the back of Sintel's head filled her eye holes, a trial). From behind, the same
// hair lies on the outside and shows; a hair inside the shell shows through the hole.
TEST(Render, HairJustOutsideTheFarWallIsHiddenThroughAHole)
{
    PolygonSoup shell = uv_sphere({0, 0, 0}, 1.0f);
    PolygonSoup open;  // the shell without the faces facing the camera (z > 0.6)
    open.points = shell.points;
    for (size_t f = 0; f < shell.num_faces(); ++f) {
        const auto face = shell.face(f);
        float z = 0.0f;
        for (const int32_t v : face) z += shell.points[size_t(v)].z / float(face.size());
        if (z <= 0.6f) open.add_face(face);
    }
    RenderParams p = small_params();
    p.default_width_px = 4.0f;  // 2 pixels of 0.015 units: a radius of 0.03, more than the hair's gap below
    Camera front = front_ortho();
    front.ortho_height = 1.5f;
    const CurveSet outside = polyline({{-0.2f, 0.0f, -1.02f}, {0.2f, 0.0f, -1.02f}});
    const CurveSet inside = polyline({{-0.2f, 0.0f, -0.9f}, {0.2f, 0.0f, -0.9f}});
    RenderScene scene;
    scene.mesh = &open;
    scene.curves = {&outside};
    EXPECT_EQ(count_red(render(scene, front, p)), 0) << "a hair behind the far wall shows through the hole";
    Camera back = front;
    back.eye = {0, 0, -10};
    EXPECT_GT(count_red(render(scene, back, p)), 50) << "seen from behind, the hair lies on the outside";
    scene.curves = {&inside};
    EXPECT_GT(count_red(render(scene, front, p)), 50) << "a hair inside the shell is seen through the hole";
    // Wound inward throughout (as the ponytail head is), the same.
    PolygonSoup inward;
    inward.points = open.points;
    for (size_t f = 0; f < open.num_faces(); ++f) {
        const auto face = open.face(f);
        std::vector<int32_t> reversed(face.rbegin(), face.rend());
        inward.add_face(reversed);
    }
    scene.mesh = &inward;
    scene.curves = {&outside};
    EXPECT_EQ(count_red(render(scene, front, p)), 0) << "inward winding";
}

TEST(Render, NearerCurveWinsAtACrossing)
{
    CurveSet near_curve = polyline({{-1, 0, 1}, {1, 0, 1}});
    CurveSet far_curve = polyline({{0, -1, -1}, {0, 1, -1}});
    RenderScene scene;
    // Far drawn after near: the depth test, not the order, must decide.
    scene.curves = {&near_curve, &far_curve};
    RenderParams p = small_params();
    p.color_by = ColorBy::File;
    p.default_width_px = 4.0f;
    Camera cam = front_ortho();
    cam.ortho_height = 4.0f;
    const RgbImage im = render(scene, cam, p);
    const float3 c0 = categorical_color(0);
    const uint8_t* centre = im.at(50, 50);
    const uint8_t* far_only = im.at(50, 20);
    // The crossing has the near layer's hue: compare which channel dominates against each layer's colour.
    auto closer = [&](const uint8_t* px, const float3& c) {
        float d = 0.0f;
        const float sum = float(px[0]) + float(px[1]) + float(px[2]) + 1.0f;
        const float csum = c.x + c.y + c.z;
        for (int k = 0; k < 3; ++k) d += std::fabs(float(px[k]) / sum - c[k] / csum);
        return d;
    };
    const float3 c1 = categorical_color(1);
    EXPECT_LT(closer(centre, c0), closer(centre, c1));
    EXPECT_LT(closer(far_only, c1), closer(far_only, c0));
}

TEST(Render, AutoFramingCentresAndFitsWithMargin)
{
    const PolygonSoup sphere = uv_sphere({5, -3, 2}, 2.0f, 64, 128);
    RenderScene scene;
    scene.mesh = &sphere;
    RenderParams p = small_params();
    p.margin = 0.1f;
    const RgbImage im = render(scene, view_camera(View::Front), p);
    int top = -1, bottom = -1, left = 100, right = -1;
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 100; ++x) {
            if (is_background(im, x, y, p)) continue;
            if (top < 0) top = y;
            bottom = y;
            left = std::min(left, x);
            right = std::max(right, x);
        }
    // The sphere spans 80% of the picture (10% margin each side): rows and columns 10..89, +-1 pixel
    // for anti-aliased edges.
    EXPECT_NEAR(top, 10, 1);
    EXPECT_NEAR(bottom, 89, 1);
    EXPECT_NEAR(left, 10, 1);
    EXPECT_NEAR(right, 89, 1);
}

TEST(Render, BadCameraIsRejected)
{
    RenderScene scene;
    const RenderParams p = small_params();
    Camera same;
    same.eye = same.target = {1, 2, 3};
    try {
        render(scene, same, p);
        FAIL() << "eye == target accepted";
    } catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("eye and target must differ"), std::string::npos) << e.what();
    }
    Camera nan_eye;
    nan_eye.eye.x = std::nanf("");
    EXPECT_THROW(render(scene, nan_eye, p), InvalidParam);
    for (float fov : {-1.0f, 170.0f, 400.0f, std::nanf("")}) {
        Camera c;
        c.fov_degrees = fov;
        try {
            render(scene, c, p);
            FAIL() << "fov " << fov << " accepted";
        } catch (const InvalidParam& e) {
            EXPECT_NE(std::string(e.what()).find("`fov` must be in (0, 170)"), std::string::npos) << e.what();
        }
    }
    Camera neg;
    neg.ortho_height = -1.0f;
    EXPECT_THROW(render(scene, neg, p), InvalidParam);
}

TEST(Render, BadSizeAndParamsAreRejected)
{
    RenderScene scene;
    auto rejects = [&](RenderParams p, const std::string& needle) {
        try {
            render(scene, front_ortho(), p);
            ADD_FAILURE() << "accepted: expected '" << needle << "'";
        } catch (const InvalidParam& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    RenderParams p = small_params();
    p.width = p.height = 0;
    rejects(p, "at least 1x1 pixels (got 0x0)");
    p = small_params();
    p.width = 100000;
    rejects(p, "at most 16384 pixels per side");
    p = small_params();
    p.width = p.height = 16000;
    rejects(p, "samples, more than");
    p = small_params();
    p.supersample = 0;
    rejects(p, "`supersample` must be in [1, 4]");
    p = small_params();
    p.color = {2, 0, 0};
    rejects(p, "`color` components must be in [0, 1]");
    p = small_params();
    p.width_scale = 0;
    rejects(p, "`width_scale` must be > 0");
    p = small_params();
    p.margin = 0.5f;
    rejects(p, "`margin` must be in [0, 0.45]");
    EXPECT_THROW(render_sheet(scene, {}, small_params()), InvalidParam);
}

TEST(Render, IdenticalPicturesForOneAndTwoThreads)
{
    // Many crossing curves of equal depth: ties are where scheduling could leak into the picture.
    const int64_t n = 400;
    std::vector<int64_t> counts(n, 8);
    CurveSet c = CurveSet::from_counts(counts);
    auto P = c.positions_for_write();
    auto strand = c.add<int32_t>(Domain::Curve, "strand");
    for (int64_t i = 0; i < n; ++i) {
        strand[i] = int32_t(i % 3);
        for (int k = 0; k < 8; ++k) {
            const float a = 0.05f * float(i) + 0.4f * float(k);
            P[i * 8 + k] = {std::cos(a) * (1.0f + 0.1f * k), std::sin(a) * (1.0f + 0.1f * k), 0.0f};
        }
    }
    const PolygonSoup sphere = uv_sphere({0, 0, -0.5f}, 1.0f);
    RenderScene scene;
    scene.curves = {&c};
    scene.mesh = &sphere;
    RenderParams p = small_params();
    p.width = p.height = 160;
    p.color_by = ColorBy::Strand;
    RgbImage one, two;
    {
        ThreadLimit limit(1);
        one = render(scene, view_camera(View::ThreeQuarter), p);
    }
    {
        ThreadLimit limit(2);
        two = render(scene, view_camera(View::ThreeQuarter), p);
    }
    EXPECT_EQ(one.rgb, two.rgb);
}

TEST(Render, ColorByReadsPointOrCurveAttributes)
{
    // Two curves, strand 0 and 1 on the curve domain; colours must be the palette's.
    std::vector<int64_t> counts{2, 2};
    CurveSet c = CurveSet::from_counts(counts);
    auto P = c.positions_for_write();
    P[0] = {-1, 1.05f, 0};
    P[1] = {1, 1.05f, 0};
    P[2] = {-1, -1.05f, 0};
    P[3] = {1, -1.05f, 0};
    auto strand = c.add<int32_t>(Domain::Curve, "strand");
    strand[0] = 0;
    strand[1] = 1;
    RenderScene scene;
    scene.curves = {&c};
    RenderParams p = small_params();
    p.color_by = ColorBy::Strand;
    p.default_width_px = 3.0f;
    const RgbImage im = render(scene, front_ortho(), p);
    const uint8_t* a = im.at(50, 39);
    const uint8_t* b = im.at(50, 60);
    EXPECT_FALSE(is_background(im, 50, 39, p));
    EXPECT_FALSE(is_background(im, 50, 60, p));
    int diff = 0;
    for (int k = 0; k < 3; ++k) diff += std::abs(int(a[k]) - int(b[k]));
    EXPECT_GT(diff, 60) << "strands 0 and 1 must get clearly different colours";
    EXPECT_TRUE(has_color_attribute(c, ColorBy::Strand));
    EXPECT_FALSE(has_color_attribute(c, ColorBy::Shape));
}

TEST(Render, CategoricalPaletteIsStableAndSeparatesNeighbours)
{
    for (int64_t v = -5; v < 200; ++v) {
        const float3 a = categorical_color(v), b = categorical_color(v + 1);
        EXPECT_EQ(a, categorical_color(v));
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(a[k], 0.0f);
            EXPECT_LE(a[k], 1.0f);
        }
        EXPECT_GT(std::fabs(a.x - b.x) + std::fabs(a.y - b.y) + std::fabs(a.z - b.z), 0.2f) << v;
    }
}

TEST(Render, SheetPlacesLabelledViewsSideBySide)
{
    const PolygonSoup sphere = uv_sphere({0, 0, 0}, 1.0f);
    RenderScene scene;
    scene.mesh = &sphere;
    RenderParams p = small_params();
    p.width = 120;
    p.height = 90;
    const std::vector<View> views{View::Front, View::Left, View::Top};
    const RgbImage sheet = render_sheet(scene, views, p);
    EXPECT_EQ(sheet.width, 360);
    EXPECT_EQ(sheet.height, 90);
    // Each view's label is dark text in its top-left corner, over the background.
    for (int v = 0; v < 3; ++v) {
        int dark = 0;
        for (int y = 0; y < 12; ++y)
            for (int x = v * 120 + 2; x < v * 120 + 40; ++x) dark += sheet.at(x, y)[0] < 128 ? 1 : 0;
        EXPECT_GT(dark, 10) << "view " << v;
    }
}

TEST(Render, PerspectiveSkipsWhatIsBehindTheEye)
{
    // Eye inside the scene: a curve behind the eye must not be drawn (it would project mirrored),
    // a segment crossing the eye plane is dropped, and what is in front is drawn.
    const CurveSet behind = polyline({{-1, 0, -3}, {1, 0, -3}});
    const CurveSet crossing = polyline({{0.2f, 0.2f, -3}, {0.2f, 0.2f, 3}});
    const CurveSet in_front = polyline({{-1, -0.5f, 3}, {1, -0.5f, 3}});
    Camera cam;
    cam.eye = {0, 0, 0};
    cam.target = {0, 0, 1};
    cam.fov_degrees = 60.0f;
    RenderParams p = small_params();
    RenderScene scene;
    scene.curves = {&behind, &crossing};
    EXPECT_EQ(count_red(render(scene, cam, p)), 0);
    scene.curves = {&behind, &crossing, &in_front};
    EXPECT_GT(count_red(render(scene, cam, p)), 20);
}
