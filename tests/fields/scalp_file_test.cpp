// Reading a scalp .vdb (fields/scalp_file.cpp) that is damaged or lies: truncated files, flipped bits
// and grids OpenVDB decodes without complaint but groom cannot use (NaN distances, an infinite voxel,
// the wrong class). Each is a ParseError naming the file, never a crash or a NaN answer.
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/mesh_io.h"
#include "kernel/memory_budget.h"
#include "support/sphere_mesh.h"
#include "test_support.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace groom {
namespace {

/// A sphere level set of radius 10 named "scalp", as other tools write one.
openvdb::FloatGrid::Ptr sphere_grid(double voxel = 1.0)
{
    openvdb::initialize();
    auto g = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(10.0f, openvdb::Vec3f(0, 0, 0), float(voxel), 3.0f);
    g->setName("scalp");
    return g;
}

void write_grid(const openvdb::FloatGrid::Ptr& g, const std::string& path)
{
    openvdb::io::File f(path);
    f.write(openvdb::GridCPtrVec{g});
    f.close();
}

/// The message of the ParseError reading `path` throws, or what happened instead.
std::string parse_error(const std::string& path)
{
    try {
        read_scalp_vdb(path);
        return "read without an error";
    }
    catch (const ParseError& e) {
        return e.what();
    }
    catch (const std::exception& e) {
        return std::string("not a ParseError: ") + e.what();
    }
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(ScalpFile, GridsOpenVdbAcceptsButGroomCannotUseAreRefused)
{
    test::TempDir dir;
    const std::string good = dir.file("good.vdb");
    write_grid(sphere_grid(), good);
    const ScalpField field = read_scalp_vdb(good);
    EXPECT_NEAR(field.distance(float3(0, 0, 0)), -10.0f, 1.1f);  // the band's clamp inside

    auto nan = sphere_grid();
    nan->tree().setValue(openvdb::Coord(10, 0, 0), std::numeric_limits<float>::quiet_NaN());
    write_grid(nan, dir.file("nan.vdb"));
    EXPECT_TRUE(contains(parse_error(dir.file("nan.vdb")), dir.file("nan.vdb") + ": grid 'scalp' holds a non-finite distance (nan) at voxel (10, 0, 0)"))
        << parse_error(dir.file("nan.vdb"));

    // A mesh whose size overflowed float was written with an infinite voxel before it was refused.
    auto inf = sphere_grid();
    inf->setTransform(openvdb::math::Transform::createLinearTransform(std::numeric_limits<double>::infinity()));
    write_grid(inf, dir.file("inf.vdb"));
    EXPECT_TRUE(contains(parse_error(dir.file("inf.vdb")), "inf.vdb: grid 'scalp' has voxel size inf")) << parse_error(dir.file("inf.vdb"));

    auto fog = sphere_grid();
    fog->setGridClass(openvdb::GRID_FOG_VOLUME);
    write_grid(fog, dir.file("fog.vdb"));
    EXPECT_TRUE(contains(parse_error(dir.file("fog.vdb")), "fog.vdb: grid 'scalp' is not a level set (class 'fog volume')"))
        << parse_error(dir.file("fog.vdb"));

    auto empty = openvdb::FloatGrid::create(3.0f);
    empty->setName("scalp");
    empty->setGridClass(openvdb::GRID_LEVEL_SET);
    write_grid(empty, dir.file("empty.vdb"));
    EXPECT_TRUE(contains(parse_error(dir.file("empty.vdb")), "empty.vdb: grid 'scalp' has no active voxels")) << parse_error(dir.file("empty.vdb"));
}

TEST(ScalpFile, DamagedFilesAreParseErrorsNeverCrashes)
{
    // Single-bit flips of a .vdb that crashed OpenVDB's own decoder (it trusts a chunk's length and
    // writes past its buffer: heap corruption, then an abort) did so in the process that read it;
    // decoding now happens in a child process, so here they are ParseErrors like any other damage.
    test::TempDir dir;
    // A length field flipped to gigabytes is then a quick bad_alloc in the reading child rather
    // than gigabytes allocated and zeroed (seconds each).
    const MemoryLimit budget(512ull << 20);
    const std::string src = dir.file("sphere.vdb");
    write_scalp(build_scalp(icosphere(float3(0, 0, 0), 10.0f, 3), {1.0f, 2.0f}), src);
    const std::string bytes = test::read_bytes(src);
    const std::string bad = dir.file("bad.vdb");
    int read_ok = 0, refused = 0, decoder_crashes = 0;
    auto attempt = [&](const std::string& what, const std::string& data) {
        test::write_text(bad, data);
        try {
            const ScalpField f = read_scalp_vdb(bad);
            ++read_ok;
            for (const float3 p : {float3(0, 3, 0), float3(0, 30, 0), float3(12, 0, 0)}) {
                EXPECT_TRUE(std::isfinite(f.distance(p))) << what;
                EXPECT_TRUE(isfinite(f.closest_point(p))) << what;
            }
        }
        catch (const ParseError& e) {
            ++refused;
            EXPECT_TRUE(contains(e.what(), bad)) << what << ": " << e.what();
            decoder_crashes += contains(e.what(), "decoder crashed");
        }
        catch (const std::exception& e) {
            ADD_FAILURE() << what << ": not a ParseError: " << e.what();
        }
    };
    for (int i = 0; i < 32; ++i) attempt("truncated to " + std::to_string(i) + "/32", bytes.substr(0, bytes.size() * i / 32));
    std::mt19937_64 rng(7);
    for (int i = 0; i < 150; ++i) {
        std::string b = bytes;
        const size_t at = rng() % b.size();
        const int bit = int(rng() % 8);
        b[at] = char(b[at] ^ (1 << bit));
        attempt("bit " + std::to_string(bit) + " of byte " + std::to_string(at), b);
    }
    EXPECT_GE(refused, 32);
    std::printf("[ info ] %d damaged files read, %d refused (%d crashed OpenVDB's decoder in the reading child)\n", read_ok, refused,
                decoder_crashes);
}

}  // namespace
}  // namespace groom
