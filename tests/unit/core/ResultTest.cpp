// Result and Status: value or error, and misuse aborts.
#include "engine/core/Result.h"

#include <gtest/gtest.h>

namespace {

core::Result<int> half(int v) {
    if (v % 2)
        return core::Error{"half(): odd value " + std::to_string(v)};
    return v / 2;
}

TEST(Result, CarriesValueOrError) {
    const auto good = half(4);
    ASSERT_TRUE(good.ok());
    EXPECT_EQ(*good, 2);
    const auto bad = half(3);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().message, "half(): odd value 3");
}

TEST(ResultDeathTest, ReadingTheValueOfAnErrorAborts) {
    EXPECT_DEATH({ [[maybe_unused]] int v = half(3).value(); }, "odd value 3");
    // The message names where the check is written, not Check.cpp.
    EXPECT_DEATH({ [[maybe_unused]] int v = half(3).value(); },
                 "Result\\.h:[0-9]+: .*value.*check `ok\\(\\)` failed: half\\(\\): odd value 3");
}

TEST(Status, DefaultIsSuccess) {
    const core::Status ok;
    EXPECT_TRUE(ok.ok());
    const core::Status failed = core::Error{"x"};
    EXPECT_FALSE(failed.ok());
    EXPECT_EQ(failed.error().message, "x");
}

} // namespace
