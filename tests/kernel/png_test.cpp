#include "kernel/io/png.h"

#include "kernel/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace groom;

TEST(Png, RoundTripsEveryPixel)
{
    test::TempDir dir;
    RgbImage im(37, 21);  // odd sizes: no row padding assumptions
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            uint8_t* p = im.at(x, y);
            p[0] = uint8_t(x * 7);
            p[1] = uint8_t(y * 11);
            p[2] = uint8_t((x * y) & 255);
        }
    write_png(im, dir.file("a.png"));
    const std::string bytes = test::read_bytes(dir.file("a.png"));
    ASSERT_GT(bytes.size(), 8u);
    EXPECT_EQ(bytes.substr(1, 3), "PNG");
    const RgbImage back = read_png(dir.file("a.png"));
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 21);
    EXPECT_EQ(back.rgb, im.rgb);
}

TEST(Png, EmptyImageIsRejectedAndNothingWritten)
{
    test::TempDir dir;
    EXPECT_THROW(write_png(RgbImage(0, 5), dir.file("b.png")), InvalidParam);
    EXPECT_FALSE(std::filesystem::exists(dir.file("b.png")));
    RgbImage bad(4, 4);
    bad.rgb.resize(5);
    EXPECT_THROW(write_png(bad, dir.file("b.png")), InvalidParam);
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(Png, GarbageAndTruncatedFilesAreParseErrors)
{
    test::TempDir dir;
    test::write_text(dir.file("x.png"), "hello, not a png");
    EXPECT_THROW(read_png(dir.file("x.png")), ParseError);
    RgbImage im(16, 16);
    write_png(im, dir.file("y.png"));
    std::string bytes = test::read_bytes(dir.file("y.png"));
    test::write_text(dir.file("z.png"), bytes.substr(0, bytes.size() / 2));
    EXPECT_THROW(read_png(dir.file("z.png")), ParseError);
    EXPECT_THROW(read_png(dir.file("missing.png")), IoError);
}
