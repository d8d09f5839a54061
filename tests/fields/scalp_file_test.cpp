// Reading a scalp .vdb (fields/scalp_file.cpp) that is damaged or lies: truncated files, flipped bits
// and grids OpenVDB decodes without complaint but groom cannot use (NaN distances, an infinite voxel,
// the wrong class). Each is a ParseError naming the file, never a crash or a NaN answer.
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/mesh_io.h"
#include "kernel/memory_budget.h"
#include "support/sphere_mesh.h"
#include "test_support.h"
#include "vdb_grid_file.h"

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

/// `grids` written to one .vdb at `path`; returns path.
std::string write_grids(const openvdb::GridCPtrVec& grids, const std::string& path)
{
    openvdb::io::File f(path);
    f.write(grids);
    f.close();
    return path;
}

/// The sphere grid under another name (and class).
openvdb::FloatGrid::Ptr renamed(const std::string& name, openvdb::GridClass cls = openvdb::GRID_LEVEL_SET, double voxel = 1.0)
{
    auto g = sphere_grid(voxel);
    g->setName(name);
    g->setGridClass(cls);
    return g;
}

/// Distances of `f` at points in and around the band.
std::vector<float> probe(const ScalpField& f)
{
    std::vector<float> d;
    for (const float3 p : {float3(0, 0, 0), float3(9.5f, 0, 0), float3(0, 10.2f, 0.3f), float3(-4, 5, 7), float3(0, 0, 30)}) d.push_back(f.distance(p));
    return d;
}

// Another program's level set is read whatever its grid's name: vdb_tool writes "mesh2ls_NAME",
// Houdini "surface" (a user trial: both were refused, "no grid named 'scalp'", with a suggested
// `groom scalp MESH -o houdini_like.vdb` that would have written over the user's file). The only
// float level set of a file is used, with the same distances as the same grid named "scalp"; so is
// a float grid without a class whose values are plainly a signed distance (pyopenvdb's FloatGrid()).
TEST(ScalpFile, AFilesOnlyLevelSetIsUsedWhateverItsName)
{
    test::TempDir dir;
    const std::string scalp = dir.file("scalp.vdb");
    write_grid(sphere_grid(), scalp);
    const std::vector<float> expected = probe(read_scalp_vdb(scalp));
    EXPECT_EQ(read_scalp_vdb(scalp).grid_name(), "scalp");

    auto density = openvdb::FloatGrid::create(0.0f);  // a fog volume beside it is no candidate
    density->setName("density");
    density->setGridClass(openvdb::GRID_FOG_VOLUME);
    density->tree().setValue(openvdb::Coord(1, 2, 3), 0.5f);
    auto vel = openvdb::Vec3SGrid::create();
    vel->setName("vel");
    const std::pair<std::string, openvdb::GridCPtrVec> files[] = {
        {"houdini.vdb", {renamed("surface")}},
        {"vdb_tool.vdb", {renamed("mesh2ls_sintel")}},
        {"with_fog.vdb", {density, renamed("surface"), vel}},
        {"no_class.vdb", {renamed("sdf", openvdb::GRID_UNKNOWN)}},
    };
    for (const auto& [name, grids] : files) {
        const ScalpField f = read_scalp_vdb(write_grids(grids, dir.file(name)));
        EXPECT_EQ(probe(f), expected) << name;
        EXPECT_NE(f.grid_name(), "scalp") << name;
    }
    EXPECT_EQ(read_scalp_vdb(dir.file("houdini.vdb")).grid_name(), "surface");
    // load_scalp (every --scalp) the same; `grid` picks one by name.
    EXPECT_EQ(probe(*load_scalp(dir.file("vdb_tool.vdb"))), expected);
    ScalpBuildParams pick;
    pick.grid = "surface";
    EXPECT_EQ(probe(*load_scalp(dir.file("with_fog.vdb"), pick)), expected);
    // A field read from another name is written back as groom's own "scalp".
    write_scalp(read_scalp_vdb(dir.file("houdini.vdb")), dir.file("again.vdb"));
    EXPECT_TRUE(test::read_scalp_grid(dir.file("again.vdb")));
}

// Several candidates, or none: refused naming the file and listing every grid (name, value type,
// class), with the way on (--scalp-grid NAME; the head's mesh), never a command that would write
// over the file.
TEST(ScalpFile, SeveralLevelSetsOrNoneAreRefusedListingTheGrids)
{
    test::TempDir dir;
    const std::string two = write_grids({renamed("left"), renamed("right", openvdb::GRID_LEVEL_SET, 0.5)}, dir.file("two.vdb"));
    const std::string msg = parse_error(two);
    EXPECT_TRUE(contains(msg, two + ": no grid is named 'scalp' and 2 are float level sets")) << msg;
    EXPECT_TRUE(contains(msg, "'left' (float, level set), 'right' (float, level set)")) << msg;
    EXPECT_TRUE(contains(msg, "--scalp-grid NAME")) << msg;
    // Either one, by name.
    EXPECT_EQ(read_scalp_vdb(two, nullptr, "left").voxel_size(), 1.0f);
    EXPECT_EQ(read_scalp_vdb(two, nullptr, "right").voxel_size(), 0.5f);
    try {
        read_scalp_vdb(two, nullptr, "middle");
        ADD_FAILURE() << "a grid the file lacks was read";
    }
    catch (const InvalidParam& e) {
        EXPECT_TRUE(contains(e.what(), "--scalp-grid middle: " + two + " has no grid of that name (found: 'left'")) << e.what();
    }

    auto density = openvdb::FloatGrid::create(0.0f);  // a float grid of no class, but not a distance
    density->setName("density");
    density->tree().setValue(openvdb::Coord(1, 2, 3), 0.5f);
    auto vel = openvdb::Vec3SGrid::create();
    vel->setName("vel");
    const std::string none = write_grids({density, vel, renamed("fog", openvdb::GRID_FOG_VOLUME)}, dir.file("none.vdb"));
    const std::string m2 = parse_error(none);
    EXPECT_TRUE(contains(m2, none + ": no grid is named 'scalp' and none is a float level set")) << m2;
    EXPECT_TRUE(contains(m2, "'density' (float, unknown), 'fog' (float, fog volume), 'vel' (vec3s, unknown)")) << m2;
    EXPECT_TRUE(contains(m2, "give --scalp the head's mesh")) << m2;
    EXPECT_FALSE(contains(m2, "-o none.vdb")) << m2;
    const std::string empty = write_grids({}, dir.file("empty.vdb"));
    EXPECT_TRUE(contains(parse_error(empty), "(found: no grids)")) << parse_error(empty);
    // A grid picked by name is still checked as any scalp is.
    try {
        read_scalp_vdb(none, nullptr, "fog");
        ADD_FAILURE() << "a fog volume was read as a scalp";
    }
    catch (const ParseError& e) {
        EXPECT_TRUE(contains(e.what(), "none.vdb: grid 'fog' is not a level set (class 'fog volume')")) << e.what();
    }
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
