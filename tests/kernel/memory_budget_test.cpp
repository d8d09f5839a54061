// The command's memory budget (kernel/memory_budget.h): scoped, checked against estimates, and never
// above what `ulimit -v` lets the process have.
#include "kernel/curve_set.h"
#include "kernel/error.h"
#include "kernel/memory_budget.h"

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>
#include <limits>

using namespace groom;

TEST(MemoryBudget, ScopedLimitIsCheckedAndRestored)
{
    const uint64_t before = memory_budget();
    {
        const MemoryLimit limit(1ull << 30);
        EXPECT_EQ(memory_budget(), 1ull << 30);
        EXPECT_NO_THROW(check_memory("test: fits", double(1ull << 30), "ask for less"));
        try {
            check_memory("test: 3 things", 1.5 * double(1ull << 30), "use a smaller `count`");
            ADD_FAILURE() << "no error";
        }
        catch (const LimitExceeded& e) {
            EXPECT_STREQ(e.what(), "test: 3 things needs about 1.5 GiB, over the 1 GiB memory budget; use a smaller `count` "
                                   "(or raise the budget with `memory` GiB)");
        }
        EXPECT_THROW(check_memory("test: inf", std::numeric_limits<double>::infinity(), "ask for less"), LimitExceeded);
        EXPECT_THROW(check_memory("test: nan", std::nan(""), "ask for less"), LimitExceeded);
        const MemoryLimit keep(0);  // 0 keeps the budget in force
        EXPECT_EQ(memory_budget(), 1ull << 30);
    }
    EXPECT_EQ(memory_budget(), before);
}

TEST(MemoryBudget, DefaultFollowsTheAddressSpaceLimit)
{
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_AS, &old), 0);
    const uint64_t unlimited = default_memory_budget();
    EXPECT_GE(unlimited, 64ull << 20);
    rlimit tight = old;
    tight.rlim_cur = rlim_t(4ull << 30);
    if (old.rlim_max != RLIM_INFINITY && old.rlim_max < tight.rlim_cur) GTEST_SKIP() << "hard limit below 4 GiB";
    ASSERT_EQ(::setrlimit(RLIMIT_AS, &tight), 0);
    const uint64_t limited = default_memory_budget();
    ASSERT_EQ(::setrlimit(RLIMIT_AS, &old), 0);
    EXPECT_EQ(limited, std::min<uint64_t>(unlimited, 3ull << 30));
}

TEST(MemoryBudget, NoteSurvivesTheExceptionThatPassesIt)
{
    EXPECT_EQ(memory_note(), "");
    try {
        const MemoryNote note("test: the big table (estimated 2 GiB)");
        EXPECT_EQ(memory_note(), "test: the big table (estimated 2 GiB)");
        throw std::bad_alloc();
    }
    catch (const std::bad_alloc&) {
        EXPECT_EQ(memory_note(), "test: the big table (estimated 2 GiB)");
    }
    {
        const MemoryLimit next_command(0);
        EXPECT_EQ(memory_note(), "");
    }
}

TEST(MemoryBudget, BytesPerElementCountEveryColumn)
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{3, 2});
    EXPECT_EQ(bytes_per_point(cs), 12.0);  // P
    cs.add<float>(Domain::Point, attr::width);
    cs.add<int64_t>(Domain::Curve, attr::id);
    EXPECT_EQ(bytes_per_point(cs), 16.0);
    EXPECT_EQ(bytes_per_curve(cs), 16.0);  // id + the offset
}
