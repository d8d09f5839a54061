// The words of `groom render` (cli/render_options.cpp); moved here from tests/ops/render_test.cpp
// with the parsers themselves.
#include "cli/render_options.h"

#include "kernel/error.h"

#include <gtest/gtest.h>

using namespace groom;
using namespace groom::cli;

TEST(RenderOptions, UnknownViewAndColorByAreRejected)
{
    EXPECT_THROW(parse_view("sideways"), InvalidParam);
    EXPECT_THROW(parse_color_by("colour"), InvalidParam);
}
