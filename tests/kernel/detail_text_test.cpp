// Detail values kept as comments in .obj (`# groom detail NAME TYPE VALUE`) and .ply (`comment groom
// detail ...`): a value that does not fit its type, words after it, or a name given twice are refused
// naming the file (and line), where before the last of two names won and an int past 32 bits wrapped.
#include "kernel/curve_set.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/detail_text.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <string>

using namespace groom;

namespace {

/// The error reading `text` as `name` gives, or "" when it reads.
std::string read_error(test::TempDir& dir, const std::string& name, const std::string& text)
{
    test::write_text(dir.file(name), text);
    try {
        read_curves(dir.file(name));
    } catch (const ParseError& e) {
        return e.what();
    }
    return "";
}

std::string obj_with(const std::string& comments) { return "v 0 0 0\nv 0 0 1\n" + comments + "l 1 2\n"; }

std::string ply_with(const std::string& comments)
{
    return "ply\nformat ascii 1.0\n" + comments +
           "element vertex 2\nproperty float x\nproperty float y\nproperty float z\nelement edge 1\nproperty int vertex1\n"
           "property int vertex2\nend_header\n0 0 0\n0 0 1\n0 1\n";
}

}  // namespace

TEST(DetailText, ValuesThatDoNotFitTheirTypeAreRefusedByLine)
{
    test::TempDir dir;
    // What reads: one of each type, the string with its spaces.
    const std::string good = "# groom detail a int -2147483648\n# groom detail b int64 5000000000\n# groom detail c float 1.5\n"
                             "# groom detail d float3 1 2 3\n# groom detail e string two words\n";
    ASSERT_EQ(read_error(dir, "good.obj", obj_with(good)), "");
    const CurveSet cs = read_curves(dir.file("good.obj"));
    EXPECT_EQ(cs.find<int32_t>(Domain::Detail, "a")[0], -2147483647 - 1);
    EXPECT_EQ(cs.find<int64_t>(Domain::Detail, "b")[0], 5000000000);
    EXPECT_EQ(cs.detail_string("e"), "two words");

    const std::string wrapped = read_error(dir, "w.obj", obj_with("# groom detail shard int 4294967297\n"));
    EXPECT_NE(wrapped.find("w.obj:3: malformed '# groom detail shard int 4294967297' (an int past the 32-bit range)"), std::string::npos) << wrapped;
    const std::string words = read_error(dir, "x.obj", obj_with("# groom detail c float 1.5 cm\n"));
    EXPECT_NE(words.find("x.obj:3:"), std::string::npos) << words;
    EXPECT_NE(words.find("(words after the value)"), std::string::npos) << words;
    const std::string type = read_error(dir, "t.obj", obj_with("# groom detail c double 1.5\n"));
    EXPECT_NE(type.find("(expected a type: float, int, int64, float3 or string)"), std::string::npos) << type;
    const std::string ply = read_error(dir, "w.ply", ply_with("comment groom detail shard int 4294967297\n"));
    EXPECT_NE(ply.find("w.ply: malformed 'comment groom detail shard int 4294967297' (an int past the 32-bit range)"), std::string::npos) << ply;
}

// The details groom reads itself keep their type and meaning: `up_axis z` had turned transform's
// axis while .usda was written Y-up; `up_axis int 1` failed later, naming no file.
TEST(DetailText, KnownDetailsMustMeanWhatGroomReads)
{
    test::TempDir dir;
    EXPECT_NE(read_error(dir, "a.obj", obj_with("# groom detail up_axis string z\n")).find("a.obj:3:"), std::string::npos);
    EXPECT_NE(read_error(dir, "b.obj", obj_with("# groom detail up_axis int 1\n")).find("(detail 'up_axis' is string)"), std::string::npos);
    EXPECT_NE(read_error(dir, "c.obj", obj_with("# groom detail units string furlong\n")).find("(units is mm, cm, m, in or metres per unit)"),
              std::string::npos);
    EXPECT_NE(read_error(dir, "d.obj", obj_with("# groom detail closed float 1\n")).find("(detail 'closed' is int)"), std::string::npos);
    ASSERT_EQ(read_error(dir, "e.obj", obj_with("# groom detail up_axis string Z\n# groom detail units string 0.3048\n")), "");
    EXPECT_EQ(read_curves(dir.file("e.obj")).detail_string("units"), "0.3048");
}

TEST(DetailText, ANameGivenTwiceIsRefused)
{
    test::TempDir dir;
    const std::string obj = read_error(dir, "twice.obj", obj_with("# groom detail shard string 0/2 run1\n# groom detail shard string 1/2 run1\n"));
    EXPECT_NE(obj.find("twice.obj:4:"), std::string::npos) << obj;
    EXPECT_NE(obj.find("(detail 'shard' given twice)"), std::string::npos) << obj;
    const std::string ply = read_error(dir, "twice.ply", ply_with("comment groom detail n int 1\ncomment groom detail n int 2\n"));
    EXPECT_NE(ply.find("(detail 'n' given twice)"), std::string::npos) << ply;
}

// Lines are counted on from the last comment (200,000 comments took 224 s: a trial), and past
// io::kMaxDetailComments a file is refused naming the line.
TEST(DetailText, ManyCommentsAreReadInLinearTimeAndBounded)
{
    test::TempDir dir;
    std::string many;
    for (size_t i = 0; i < io::kMaxDetailComments; ++i) many += "# groom detail k" + std::to_string(i) + " int " + std::to_string(i) + "\n";
    ASSERT_EQ(read_error(dir, "many.obj", obj_with(many)), "");
    EXPECT_EQ(read_curves(dir.file("many.obj")).find<int32_t>(Domain::Detail, "k4095")[0], 4095);
    const std::string e = read_error(dir, "more.obj", obj_with(many + "# groom detail one_more int 1\n"));
    EXPECT_NE(e.find("more.obj:" + std::to_string(io::kMaxDetailComments + 3) + ": more than 4096"), std::string::npos) << e;
}
