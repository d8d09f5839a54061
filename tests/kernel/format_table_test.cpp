// The format table: every row that writes a format reads it back, each row tells the truth about
// which attributes it keeps, the lists in help texts come from it, and formats groom cannot read are
// refused by name with a way forward.
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/format_table.h"
#include "kernel/io/mesh_io.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace groom;
using groom::test::TempDir;
using groom::test::write_text;

namespace {

CurveSet curves_with_columns()
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{3, 2});
    auto P = cs.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = float3(0.5f * float(i), 1.0f, -0.25f * float(i));
    auto w = cs.add<float>(Domain::Point, attr::width);
    for (size_t i = 0; i < w.size(); ++i) w[i] = 0.01f * float(i + 1);
    cs.add<float3>(Domain::Point, "Cd")[1] = {1, 0, 0};
    cs.add<int32_t>(Domain::Point, "segment");
    auto id = cs.add<int64_t>(Domain::Curve, attr::id);
    id[0] = 7, id[1] = 9;
    cs.add<float>(Domain::Curve, "clump");
    cs.add<float>(Domain::Detail, "scale")[0] = 2.0f;
    return cs;
}

std::string message_of(const std::function<void()>& f)
{
    try {
        f();
    }
    catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST(FormatTable, HelpListsComeFromTheRows)
{
    EXPECT_EQ(io::format_list(io::kReadCurves), ".usda .obj .ply .hair");
    EXPECT_EQ(io::format_list(io::kWriteCurves), ".usda .obj .ply .hair");
    EXPECT_EQ(io::format_list(io::kReadMesh, ", "), ".obj, .ply, .off, .stl");
    EXPECT_EQ(io::format_list(io::kWriteMesh), ".obj .ply");
    for (const io::Format& f : io::formats()) {
        EXPECT_EQ(io::format_by_extension(f.extension), &f) << f.extension;
        // A row either does something or says why it does not, never neither.
        EXPECT_NE(f.caps() == 0, f.refusal.empty()) << f.extension;
    }
}

TEST(FormatTable, EveryCurveWriterReadsBackAndKeepsWhatItSays)
{
    const CurveSet src = curves_with_columns();
    TempDir dir;
    int rows = 0;
    for (const io::Format& f : io::formats()) {
        if (!f.can(io::kWriteCurves)) continue;
        ++rows;
        const std::string path = dir.file("a." + std::string(f.extension));
        write_curves(src, path);
        const CurveSet back = read_curves(path);
        ASSERT_EQ(back.num_points(), src.num_points()) << path;
        for (size_t i = 0; i < src.num_points(); ++i) EXPECT_EQ(back.positions()[i], src.positions()[i]) << path << " point " << i;
        // Every column the table says survives is in the file read back; every one it says is lost is not.
        const std::vector<std::string> lost = attributes_dropped(src, path);
        for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) {
            for (const Attribute& a : src.attributes(d).all()) {
                if (a.name == attr::P) continue;
                const std::string key = std::string(domain_name(d)) + " " + a.name;
                const bool said_lost = std::find(lost.begin(), lost.end(), key) != lost.end();
                EXPECT_EQ(back.attributes(d).find(a.name) != nullptr, !said_lost) << path << ": " << key;
            }
        }
    }
    EXPECT_EQ(rows, 4);
}

TEST(FormatTable, TextUsdReadsAsUsdaAndBinaryIsRefusedWithAWayForward)
{
    TempDir dir;
    write_curves(curves_with_columns(), dir.file("a.usda"));
    std::filesystem::copy_file(dir.file("a.usda"), dir.file("a.usd"));
    EXPECT_EQ(read_curves(dir.file("a.usd")).num_points(), 5u);

    write_text(dir.file("crate.usd"), std::string("PXR-USDC") + std::string(80, '\0'));
    const std::string crate = message_of([&] { read_curves(dir.file("crate.usd")); });
    EXPECT_NE(crate.find("crate.usd: a binary USD crate file"), std::string::npos) << crate;
    EXPECT_NE(crate.find("usdcat"), std::string::npos) << crate;
}

TEST(FormatTable, UnreadableFormatsAreRefusedByName)
{
    TempDir dir;
    for (const char* name : {"a.usdc", "a.usdz", "a.abc"}) write_text(dir.file(name), "x");
    const std::string usdc = message_of([&] { read_curves(dir.file("a.usdc")); });
    EXPECT_NE(usdc.find("no OpenUSD package"), std::string::npos) << usdc;
    EXPECT_NE(usdc.find("usdcat FILE.usdc -o FILE.usda"), std::string::npos) << usdc;
    const std::string abc = message_of([&] { read_curves(dir.file("a.abc")); });
    EXPECT_NE(abc.find("no Alembic package"), std::string::npos) << abc;
    EXPECT_NE(abc.find("export the curves as .usda"), std::string::npos) << abc;
    const std::string write_abc = message_of([&] { write_curves(curves_with_columns(), dir.file("out.abc")); });
    EXPECT_NE(write_abc.find("no Alembic package"), std::string::npos) << write_abc;
    // Writing says what to write instead, not how to export an input.
    EXPECT_NE(write_abc.find("not written here"), std::string::npos) << write_abc;
    EXPECT_NE(write_abc.find("write .usda"), std::string::npos) << write_abc;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.abc")));
    const std::string write_usdc = message_of([&] { write_curves(curves_with_columns(), dir.file("out.usdc")); });
    EXPECT_NE(write_usdc.find("usdcat FILE.usda -o FILE.usdc"), std::string::npos) << write_usdc;
    // Known format, wrong kind: says what the file is and what would do.
    const std::string off = message_of([&] { read_curves(dir.file("head.off")); });
    EXPECT_NE(off.find("OFF mesh files are not read as curves (expected .usda, .obj, .ply, .hair)"), std::string::npos) << off;
    write_text(dir.file("strands.hair"), "x");
    const std::string hair = message_of([&] { read_mesh(dir.file("strands.hair")); });
    EXPECT_NE(hair.find("files are not read as meshes (expected .obj, .ply, .off, .stl)"), std::string::npos) << hair;  // was "meshs"
    const std::string unknown = message_of([&] { read_mesh(dir.file("x.xyz")); });
    EXPECT_NE(unknown.find("unknown mesh format '.xyz' (expected .obj, .ply, .off, .stl)"), std::string::npos) << unknown;
}
