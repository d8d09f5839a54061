// Shape names and numbers as --dominant and --shapes take them (cli/curl_options.cpp); moved here from
// tests/ops/curl_shapes_test.cpp with curl_shape_from_string itself.
#include "cli/curl_options.h"

#include <gtest/gtest.h>

#include <string>

using namespace groom;
using namespace groom::cli;

TEST(CurlOptions, ShapeNamesAndNumbersFollowTheTalk)
{
    const char* names[] = {"lame", "polygon", "ellipse", "circle", "rose"};
    for (int i = 0; i < 5; ++i) {
        EXPECT_EQ(curl_shape_from_string(names[i]), i);
        EXPECT_EQ(curl_shape_from_string(std::to_string(i)), i);
    }
    EXPECT_EQ(curl_shape_from_string("square"), -1);
    EXPECT_EQ(curl_shape_from_string("5"), -1);
    EXPECT_EQ(curl_shape_from_string("-1"), -1);
    EXPECT_EQ(curl_shape_from_string(""), -1);
}
