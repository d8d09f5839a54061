// Regressions found by the op fuzz harness (fuzz/ops_fuzz.cpp) in the scalp field: each input is
// the smallest construction that reproduced the fuzzer's crash, and the test checks the clean
// groom error that replaced it.
#include "fields/scalp_field.h"
#include "kernel/error.h"

#include <gtest/gtest.h>

namespace groom {
namespace {

PolygonSoup tetrahedron(float size)
{
    PolygonSoup s;
    s.points = {{0, 0, 0}, {size, 0, 0}, {0, size, 0}, {0, 0, size}};
    for (auto f : {std::vector<int32_t>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}) s.add_face(f);
    return s;
}

// op_project, op_cull, op_hairline: a mesh 1e-4 across (automatic voxel 6.8e-7) or an explicit voxel
// of 1e-6 (on a mesh small enough for the memory budget) made OpenVDB throw ArithmeticError ("Non-zero scale values required") from inside
// meshToVolume's task group, which ended the process (std::terminate); the CLI would have called it
// an "unexpected failure". Now InvalidGeometry naming the voxel and the smallest one OpenVDB takes.
TEST(OpFuzz, VoxelTooSmallForOpenVdbIsRefusedNamingIt)
{
    try {
        build_scalp(tetrahedron(1e-4f));
        FAIL() << "a mesh 1e-4 across was converted";
    }
    catch (const InvalidGeometry& e) {
        EXPECT_NE(std::string(e.what()).find("voxel size"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("scale the mesh up"), std::string::npos) << e.what();
    }
    ScalpBuildParams p;
    p.voxel_size = 1e-6f;  // on a mesh 1e-5 across: 17 voxels, well inside the budget
    try {
        build_scalp(tetrahedron(1e-5f), p);
        FAIL() << "voxel 1e-6 was accepted";
    }
    catch (const InvalidGeometry& e) {
        EXPECT_NE(std::string(e.what()).find("`voxel`"), std::string::npos) << e.what();
    }
    // The smallest accepted voxel still builds (h = 2e-5 on a mesh 1e-3 across: 50 voxels).
    p.voxel_size = 2e-5f;
    const ScalpField f = build_scalp(tetrahedron(1e-3f), p);
    EXPECT_NEAR(f.voxel_size(), 2e-5f, 1e-9f);
    EXPECT_LT(f.distance({1e-4f, 1e-4f, 1e-4f}), 0.0f);
}

}  // namespace
}  // namespace groom
