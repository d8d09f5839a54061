// Library messages name parameters as `snake_case`; the command line shows the options a user typed.
#include "cli/command.h"

#include <gtest/gtest.h>

using groom::cli::with_option_names;

TEST(OptionNames, ParametersBecomeTheCommandsOptions)
{
    const std::vector<std::string> options{"knot-length", "strands", "scalp"};
    EXPECT_EQ(with_option_names("braid: `knot_length` must be > 0 (got -1)", options), "braid: --knot-length must be > 0 (got -1)");
    EXPECT_EQ(with_option_names("`strands` 9 with `knot_length` 0", options), "--strands 9 with --knot-length 0");
    // Not an option of this command, not an identifier, or not closed: left as written.
    EXPECT_EQ(with_option_names("curl: `amplitude` too small", options), "curl: `amplitude` too small");
    EXPECT_EQ(with_option_names("make one with `groom scalp MESH -o x.vdb`", options), "make one with `groom scalp MESH -o x.vdb`");
    EXPECT_EQ(with_option_names("an odd ` quote", options), "an odd ` quote");
    EXPECT_EQ(with_option_names("", options), "");
}
