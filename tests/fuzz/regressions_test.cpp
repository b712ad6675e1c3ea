// Replays every input that once crashed a fuzzer (tests/fuzz/regressions/<target>/) and the
// seed corpora (tests/fuzz/corpus/<target>/) through the same entry points as the fuzzers, in
// the ordinary build. A regression shows up as a crash, a sanitizer report in the sanitizer
// build, or an unexpected exception (which fails the test).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "fuzz_entry.h"

namespace fs = std::filesystem;

namespace prism::fuzz {
namespace {

const char *Targets[] = {"pbrt", "ply", "obj", "gltf", "image"};

std::vector<fs::path> InputsUnder(const fs::path &dir) {
    std::vector<fs::path> files;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return files;
    for (const auto &e : fs::directory_iterator(dir))
        if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

size_t Replay(const std::string &kind) {
    size_t n = 0;
    for (const char *target : Targets) {
        for (const fs::path &p : InputsUnder(fs::path(PRISM_TEST_DATA_DIR) / kind / target)) {
            std::ifstream in(p, std::ios::binary);
            std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                       std::istreambuf_iterator<char>());
            SCOPED_TRACE(p.string());
            try {
                EXPECT_TRUE(FuzzByName(target, bytes.data(), bytes.size()));
            } catch (const std::exception &e) {
                ADD_FAILURE() << p << ": unexpected exception: " << e.what();
            }
            ++n;
        }
    }
    return n;
}

TEST(FuzzRegressions, ReplayWithoutFailure) {
    size_t n = Replay("regressions");
    std::printf("replayed %zu regression inputs\n", n);
    EXPECT_GT(n, 0u);
}

TEST(FuzzRegressions, SeedCorporaParse) {
    size_t n = Replay("corpus");
    std::printf("replayed %zu seed inputs\n", n);
    EXPECT_GE(n, 5u);
}

TEST(FuzzRegressions, UnknownTargetIsRejected) {
    uint8_t byte = 0;
    EXPECT_FALSE(FuzzByName("nope", &byte, 1));
}

}  // namespace
}  // namespace prism::fuzz
