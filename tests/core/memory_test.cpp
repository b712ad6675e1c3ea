// The memory budget helpers: size parsing for --max-memory, formatting, the default.
#include <gtest/gtest.h>

#include "core/memory.h"

namespace prism {
namespace {

TEST(Memory, ParsesSizesWithBinaryUnits) {
    uint64_t b = 0;
    EXPECT_TRUE(ParseMemorySize("1048576", &b));
    EXPECT_EQ(b, 1048576u);
    EXPECT_TRUE(ParseMemorySize("512M", &b));
    EXPECT_EQ(b, 512ull << 20);
    EXPECT_TRUE(ParseMemorySize("8G", &b));
    EXPECT_EQ(b, 8ull << 30);
    EXPECT_TRUE(ParseMemorySize("8gb", &b));
    EXPECT_EQ(b, 8ull << 30);
    EXPECT_TRUE(ParseMemorySize("1.5GiB", &b));
    EXPECT_EQ(b, 3ull << 29);
    EXPECT_TRUE(ParseMemorySize("100K", &b));
    EXPECT_EQ(b, 102400u);
    EXPECT_TRUE(ParseMemorySize("2T", &b));
    EXPECT_EQ(b, 2ull << 40);
}

TEST(Memory, RejectsMalformedSizes) {
    uint64_t b = 0;
    for (const char *s : {"", "0", "-1G", "G", "12Q", "1e30", "nan", "inf", "1.5.2M", " 5M", "0.1"})
        EXPECT_FALSE(ParseMemorySize(s, &b)) << s;
}

TEST(Memory, FormatsBytes) {
    EXPECT_EQ(FormatBytes(100), "100 bytes");
    EXPECT_EQ(FormatBytes(1536), "1.5 KiB");
    EXPECT_EQ(FormatBytes(512ull << 20), "512 MiB");
    EXPECT_EQ(FormatBytes(3ull << 29), "1.5 GiB");
}

TEST(Memory, DefaultIsThreeQuartersOfRam) {
    uint64_t ram = PhysicalMemoryBytes();
    ASSERT_GT(ram, 0u);
    EXPECT_EQ(DefaultMemoryBudget(), ram / 4 * 3);
    EXPECT_EQ(EffectiveMemoryBudget(0), DefaultMemoryBudget());
    EXPECT_EQ(EffectiveMemoryBudget(12345), 12345u);
}

}  // namespace
}  // namespace prism
