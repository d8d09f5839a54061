// BrickMap against its definition: trilinear interpolation of the voxels of a sparse OpenVDB grid,
// answered only where all 8 corners are active. A linear function is reproduced exactly by
// trilinear interpolation, so every answer is checked against a closed form, across leaf borders
// (the bricks' copied border layers), at negative coordinates and at the band's edge.
#include "fields/brick_map.h"
#include "kernel/rng.h"

#include <openvdb/tree/LeafManager.h>

#include <gtest/gtest.h>

#include <cmath>

namespace groom {
namespace {

float linear(float x, float y, float z) { return 0.3f * x - 0.2f * y + 0.7f * z + 1.0f; }

TEST(BrickMap, TrilinearWhereAllCornersAreActiveAndNowhereElse)
{
    openvdb::initialize();
    // A spherical shell of active voxels, radius 20 +- 3, centred off the origin so the band
    // spans negative and positive coordinates and many partially filled leaves.
    openvdb::FloatGrid grid(0.0f);
    auto acc = grid.getAccessor();
    const openvdb::Vec3f center(-3.5f, 2.25f, 0.5f);
    for (int x = -30; x <= 30; ++x)
        for (int y = -30; y <= 30; ++y)
            for (int z = -30; z <= 30; ++z) {
                const float r = (openvdb::Vec3f(float(x), float(y), float(z)) - center).length();
                if (std::fabs(r - 20.0f) <= 3.0f) acc.setValueOn(openvdb::Coord(x, y, z), linear(float(x), float(y), float(z)));
            }

    openvdb::tree::LeafManager<const openvdb::FloatTree> leaves(grid.tree());
    std::vector<openvdb::Coord> origins(leaves.leafCount());
    for (size_t i = 0; i < origins.size(); ++i) origins[i] = leaves.leaf(i).origin();
    detail::BrickMap map;
    map.allocate(origins);
    for (size_t i = 0; i < origins.size(); ++i) {
        detail::BandValue* brick = map.brick(i);
        for (auto it = leaves.leaf(i).cbeginValueOn(); it; ++it) {
            const openvdb::Coord l = it.getCoord() - origins[i];
            brick[detail::BrickMap::index(l.x(), l.y(), l.z())] = detail::BandValue{*it, 1.0f, -2.0f, 3.0f};
        }
    }
    map.fill_borders();

    int answered = 0, refused = 0, straddling = 0;
    for (uint64_t i = 0; i < 200000; ++i) {
        Rng rng(5, i);
        const float x = rng.uniform(-28.0f, 28.0f), y = rng.uniform(-28.0f, 28.0f), z = rng.uniform(-28.0f, 28.0f);
        const openvdb::Coord c0(int(std::floor(x)), int(std::floor(y)), int(std::floor(z)));
        bool all_on = true;
        for (int k = 0; k < 8; ++k) all_on &= acc.isValueOn(c0.offsetBy(k & 1, (k >> 1) & 1, (k >> 2) & 1));
        detail::BandValue v;
        const bool ok = map.sample(x, y, z, v);
        ASSERT_EQ(ok, all_on) << "at " << x << " " << y << " " << z;
        if (!ok) {
            ++refused;
            continue;
        }
        ++answered;
        straddling += ((c0.x() & 7) == 7) || ((c0.y() & 7) == 7) || ((c0.z() & 7) == 7);
        // Float rounding of values up to ~40 over three lerps: 1e-4 absolute.
        ASSERT_NEAR(v.d, linear(x, y, z), 1e-4f) << "at " << x << " " << y << " " << z;
        ASSERT_EQ(v.nx, 1.0f);
        ASSERT_EQ(v.ny, -2.0f);
        ASSERT_EQ(v.nz, 3.0f);
    }
    // Enough of each kind for the checks to mean something, cells across leaf borders included.
    EXPECT_GT(answered, 20000);
    EXPECT_GT(refused, 20000);
    EXPECT_GT(straddling, 5000);

    detail::BandValue v;
    EXPECT_FALSE(map.sample(std::nanf(""), 0.0f, 20.0f, v));
    EXPECT_FALSE(map.sample(1e20f, 0.0f, 0.0f, v));
    EXPECT_FALSE(map.sample(500.0f, 500.0f, 500.0f, v));  // no brick there
}

TEST(BrickMap, EmptyMapAnswersNothing)
{
    detail::BrickMap map;
    map.allocate({});
    map.fill_borders();
    detail::BandValue v;
    EXPECT_FALSE(map.sample(0.5f, 0.5f, 0.5f, v));
}

}  // namespace
}  // namespace groom
