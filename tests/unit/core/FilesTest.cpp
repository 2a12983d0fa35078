// Whole-file reads and atomic writes.
#include "support/TestSupport.h"

#include "engine/core/Files.h"

#include <fstream>

namespace {

TEST(Files, WriteAtomicThenRead) {
    test::TempDir dir;
    ASSERT_TRUE(core::writeFileAtomic(dir / "a.txt", std::string("hello")).ok());
    const auto bytes = core::readFile(dir / "a.txt");
    ASSERT_TRUE(bytes.ok());
    EXPECT_EQ(std::string(bytes->begin(), bytes->end()), "hello");
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path()))
        ++files;
    EXPECT_EQ(files, 1u) << "no temporary file may remain";
}

TEST(Files, FailedWriteLeavesNothing) {
    test::TempDir dir;
    const auto status = core::writeFileAtomic(dir / "missing-dir" / "a.txt", std::string("x"));
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("a.txt"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(dir / "missing-dir"));
}

TEST(Files, ReadMissingOrTooLargeNamesThePath) {
    test::TempDir dir;
    auto missing = core::readFile(dir / "nope.bin");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("nope.bin"), std::string::npos);
    std::ofstream(dir / "big.bin") << std::string(100, 'x');
    auto big = core::readFile(dir / "big.bin", 10);
    ASSERT_FALSE(big.ok());
    EXPECT_NE(big.error().message.find("over the limit"), std::string::npos);
}

} // namespace
