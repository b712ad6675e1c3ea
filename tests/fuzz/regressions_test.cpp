// Replays every input that once crashed a fuzzer (tests/fuzz/regressions/<target>/) and the
// seed corpora (tests/fuzz/corpus/<target>/) through the same entry points as the fuzzers, in
// the ordinary build. A regression shows up as a crash, a sanitizer report in the sanitizer
// build, or an unexpected exception (which fails the test). Seeds must also be accepted by
// their reader, except those named "invalid-*" (which must be rejected).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "core/error.h"
#include "fuzz_entry.h"
#include "scene/pbrt_parser.h"

namespace fs = std::filesystem;

namespace prism::fuzz {
namespace {

const char *Targets[] = {"pbrt",  "ply",       "stl",     "obj", "gltf",
                         "image", "gltf_json", "texture", "bsdf"};

std::vector<fs::path> InputsUnder(const fs::path &dir) {
    std::vector<fs::path> files;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return files;
    for (const auto &e : fs::directory_iterator(dir))
        if (e.is_regular_file() && e.path().filename().string()[0] != '.')
            files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

// Replays kind/<target>/*. With checkSeeds, an input must be accepted (no SceneError or
// image-reader error), or rejected if its name starts with "invalid-".
size_t Replay(const std::string &kind, bool checkSeeds = false) {
    size_t n = 0;
    for (const char *target : Targets) {
        for (const fs::path &p : InputsUnder(fs::path(PRISM_TEST_DATA_DIR) / kind / target)) {
            std::ifstream in(p, std::ios::binary);
            std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                       std::istreambuf_iterator<char>());
            SCOPED_TRACE(p.string());
            try {
                std::string rejected;
                EXPECT_TRUE(FuzzByName(target, bytes.data(), bytes.size(), &rejected));
                bool invalid = p.filename().string().rfind("invalid-", 0) == 0;
                if (checkSeeds && invalid)
                    EXPECT_FALSE(rejected.empty()) << p << ": a seed marked invalid was accepted";
                else if (checkSeeds)
                    EXPECT_EQ(rejected, "") << p << ": the seed does not parse";
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
    size_t n = Replay("corpus", true);
    std::printf("replayed %zu seed inputs\n", n);
    EXPECT_GE(n, 5u);
}

// The seed check itself: a seed that does not parse fails it.
TEST(FuzzRegressions, SeedCheckSeesRejections) {
    std::string bad = "WorldBegin\nShape \"sphere\" \"float radius\" [ 1\n", rejected;
    ASSERT_TRUE(
        FuzzByName("pbrt", reinterpret_cast<const uint8_t *>(bad.data()), bad.size(), &rejected));
    EXPECT_NE(rejected, "");
    std::string good = "WorldBegin\nShape \"sphere\"\nWorldEnd\n";
    rejected.clear();
    FuzzByName("pbrt", reinterpret_cast<const uint8_t *>(good.data()), good.size(), &rejected);
    EXPECT_EQ(rejected, "");
}

// regressions/pbrt/include-dev-zero is refused by the fuzz entry's include confinement (/dev is
// outside its directory) before the file reader's own device check. This reaches that check:
// with confinement off, an Include of a device must be refused as not a regular file. /dev/null
// rather than /dev/zero: without the check it reads as an empty file and parses, so the test
// fails instead of hanging.
TEST(FuzzRegressions, IncludeOfADeviceIsRefusedByTheReader) {
    PbrtParseOptions opts;
    opts.confineIncludes = false;
    Diagnostics diag(false);
    try {
        ParsePbrtString("WorldBegin\nInclude \"/dev/null\"\nWorldEnd\n",
                        (fs::temp_directory_path() / "main.pbrt").string(), diag, opts);
        ADD_FAILURE() << "an Include of /dev/null was read";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
}

TEST(FuzzRegressions, UnknownTargetIsRejected) {
    uint8_t byte = 0;
    EXPECT_FALSE(FuzzByName("nope", &byte, 1));
}

}  // namespace
}  // namespace prism::fuzz
