// The memory budget helpers: size parsing for --max-memory, formatting, the default, the
// cumulative MemoryBudget and the BVH and film estimates.
#include "core/memory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>
#include <vector>

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

TEST(MemoryBudget, AccumulatesAndThrowsOnceTheSumExceedsTheLimit) {
    MemoryBudget budget(1000);
    EXPECT_EQ(budget.Limit(), 1000u);
    budget.Charge(400, "mesh \"a\"");
    budget.Charge(400, "mesh \"b\"");
    EXPECT_EQ(budget.Used(), 800u);
    EXPECT_EQ(budget.Remaining(), 200u);
    EXPECT_TRUE(budget.Fits(200));
    EXPECT_FALSE(budget.Fits(201));
    // Each is under the limit; the third is refused and not added.
    try {
        budget.Charge(400, "mesh \"c\"", FileLoc{"scene.pbrt", 7, 3});
        FAIL() << "no error";
    } catch (const MemoryBudgetError &e) {
        EXPECT_EQ(std::string(e.what()),
                  "scene.pbrt:7:3: error: mesh \"c\" needs about 400 bytes; with 800 bytes already "
                  "committed that exceeds the memory budget of 1000 bytes");
        EXPECT_EQ(e.Requested(), 400u);
        EXPECT_EQ(e.Committed(), 800u);
        EXPECT_EQ(e.Limit(), 1000u);
    }
    EXPECT_EQ(budget.Used(), 800u);
    budget.Charge(200, "exactly the rest");
    EXPECT_EQ(budget.Remaining(), 0u);
    EXPECT_THROW(budget.Charge(1, "one byte"), MemoryBudgetError);
    budget.Release(300);
    EXPECT_EQ(budget.Used(), 700u);
    budget.Release(5000);
    EXPECT_EQ(budget.Used(), 0u);
}

TEST(MemoryBudget, ItemAloneOverTheLimitSaysSo) {
    MemoryBudget budget(1 << 20);
    budget.Charge(100, "scene file");
    try {
        budget.Charge(3ull << 20, "image 1024x1024");
        FAIL() << "no error";
    } catch (const SceneError &e) {  // a SceneError: exit status 2 and the usual catch sites
        EXPECT_EQ(e.Message(),
                  "image 1024x1024 needs about 3.0 MiB, more than the memory budget of 1.0 MiB");
    }
    // Check throws as Charge would, adding nothing.
    EXPECT_THROW(budget.Check(2ull << 20, "x"), MemoryBudgetError);
    EXPECT_NO_THROW(budget.Check(1000, "x"));
    EXPECT_EQ(budget.Used(), 100u);
    // Huge requests do not wrap around.
    EXPECT_THROW(budget.Charge(std::numeric_limits<uint64_t>::max(), "x"), MemoryBudgetError);
    EXPECT_EQ(budget.Used(), 100u);
}

TEST(MemoryBudget, ZeroMeansTheDefault) {
    EXPECT_EQ(MemoryBudget(0).Limit(), DefaultMemoryBudget());
    EXPECT_EQ(MemoryBudget().Limit(), DefaultMemoryBudget());
}

TEST(MemoryBudget, ParallelChargesNeverExceedTheLimit) {
    MemoryBudget budget(100000);
    std::vector<std::thread> threads;
    std::vector<int> accepted(4, 0);
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (int i = 0; i < 10000; ++i) try {
                    budget.Charge(7, "piece");
                    ++accepted[size_t(t)];
                } catch (const MemoryBudgetError &) {
                }
        });
    for (std::thread &t : threads) t.join();
    int total = accepted[0] + accepted[1] + accepted[2] + accepted[3];
    EXPECT_EQ(total, 100000 / 7);
    EXPECT_EQ(budget.Used(), uint64_t(total) * 7);
}

TEST(MemoryBudget, BvhEstimate) {
    EXPECT_EQ(EstimateBvhBytes(0, 0), kBvhFixedBytes);
    EXPECT_EQ(EstimateBvhBytes(1000000, 0), 112000000u + (1u << 20));
    EXPECT_EQ(EstimateBvhBytes(0, 10), 3200u + (1u << 20));
    EXPECT_EQ(EstimateBvhBytes(1000, 10), 112000u + 3200u + (1u << 20));
    // At least the measured peaks quoted in core/memory.h (107 bytes/triangle, 290/user prim).
    EXPECT_GE(EstimateBvhBytes(100000, 0), 100000u * 107);
    EXPECT_GE(EstimateBvhBytes(0, 100000), 100000u * 290);
    EXPECT_EQ(EstimateBvhBytes(std::numeric_limits<uint64_t>::max(), 1),
              std::numeric_limits<uint64_t>::max());
}

TEST(MemoryBudget, FilmEstimate) {
    // One 16x16 tile, box filter r = 0.5: film 32, image 12, encoded 12 bytes per pixel, and a
    // 17x17 tile of 32-byte pixels.
    EXPECT_EQ(EstimateFilmBytes(16, 16, 0.5, 0.5), 256u * 56 + 17u * 17 * 32);
    // Gaussian r = 2: two pixels of margin on each side, 20x20.
    EXPECT_EQ(EstimateFilmBytes(16, 16, 2, 2), 256u * 56 + 20u * 20 * 32);
    // 1920x1080: 120x68 tiles, each one pixel wider and taller.
    EXPECT_EQ(EstimateFilmBytes(1920, 1080, 0.5, 0.5),
              1920u * 1080 * 56 + uint64_t(1920 + 120) * (1080 + 68) * 32);
    // Whole tiles with the box filter: 92.125 bytes per pixel, as documented.
    EXPECT_EQ(EstimateFilmBytes(1600, 1600, 0.5, 0.5), uint64_t(1600 * 1600 * 92.125));
    // Anisotropic radius, 8-pixel tiles, partial tiles.
    EXPECT_EQ(EstimateFilmBytes(10, 3, 1.5, 0.5, 8),
              30u * 56 + uint64_t(10 + 2 * (1 + 2)) * (3 + 1 * 1) * 32);
    EXPECT_EQ(EstimateFilmBytes(0, 100, 0.5, 0.5), 0u);
    const uint64_t kMax = std::numeric_limits<uint64_t>::max();
    EXPECT_EQ(EstimateFilmBytes(uint64_t(1) << 40, uint64_t(1) << 40, 0.5, 0.5), kMax);
    EXPECT_EQ(EstimateFilmBytes(kMax, kMax, 32, 32), kMax);
    EXPECT_EQ(EstimateFilmBytes(16, 16, std::nan(""), -1), 256u * 56 + 256u * 32);
}

}  // namespace
}  // namespace prism
