// PolygonSoup's append (kernel/polygon_soup.h): several meshes joined into one, faces and texture
// coordinates renumbered.
#include "kernel/error.h"
#include "kernel/polygon_soup.h"

#include <gtest/gtest.h>

#include <vector>

using namespace groom;

TEST(PolygonSoupAppend, RenumbersFacesAndTextureCoordinates)
{
    // A triangle without texture coordinates, then a quad with them: the quad's indices follow the
    // triangle's vertices, its corners' texture coordinates follow the first mesh's (none), and the
    // triangle's corners get -1 (none).
    PolygonSoup a;
    a.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const int32_t tri[3] = {0, 1, 2};
    a.add_face(tri);
    PolygonSoup b;
    b.points = {{5, 0, 0}, {6, 0, 0}, {6, 1, 0}, {5, 1, 0}};
    b.uvs = {0, 0, 1, 0, 1, 1, 0, 1};
    const int32_t quad[4] = {0, 1, 2, 3}, quad_uv[4] = {3, 2, 1, -1};
    b.add_face(quad, quad_uv);
    append(a, b, "a + b");
    ASSERT_EQ(a.points.size(), 7u);
    ASSERT_EQ(a.num_faces(), 2u);
    EXPECT_EQ(std::vector<int32_t>(a.face(1).begin(), a.face(1).end()), (std::vector<int32_t>{3, 4, 5, 6}));
    EXPECT_EQ(a.face_uv_indices, (std::vector<int32_t>{-1, -1, -1, 3, 2, 1, -1}));
    EXPECT_EQ(a.uvs.size(), 8u);
    // The other way round: the first mesh's coordinates stay, the second's corners have none.
    PolygonSoup c = b;
    PolygonSoup t;
    t.points = a.points;
    t.add_face(tri);
    append(c, t, "b + a");
    EXPECT_EQ(c.face_uv_indices, (std::vector<int32_t>{3, 2, 1, -1, -1, -1, -1}));
    EXPECT_EQ(std::vector<int32_t>(c.face(1).begin(), c.face(1).end()), (std::vector<int32_t>{4, 5, 6}));
    // Both with texture coordinates: the second's follow the first's.
    PolygonSoup d = b;
    append(d, b, "b + b");
    EXPECT_EQ(d.uvs.size(), 16u);
    EXPECT_EQ(d.face_uv_indices, (std::vector<int32_t>{3, 2, 1, -1, 7, 6, 5, -1}));
    EXPECT_EQ(std::vector<int32_t>(d.face(1).begin(), d.face(1).end()), (std::vector<int32_t>{4, 5, 6, 7}));
}
