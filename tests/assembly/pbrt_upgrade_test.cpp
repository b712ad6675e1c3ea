// A pbrt-v3 scene and pbrt-v4's `pbrt --upgrade` of it render the same image (tests/upgrade:
// each NAME.pbrt beside the NAME.v4.pbrt pbrt-v4 wrote), the first read by pbrt-v3's rules and
// the second by pbrt-v4's.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/error.h"
#include "scene/load_scene.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/shared.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

int RulesOf(const std::string &path) {
    Diagnostics diag;
    return LoadScene(path, diag).pbrtVersion.version;
}

TEST(PbrtUpgrade, AnUpgradedSceneRendersTheSameImage) {
    int pairs = 0;
    for (const fs::directory_entry &e : fs::directory_iterator(Source + "/tests/upgrade")) {
        const std::string name = e.path().filename().string();
        if (e.path().extension() != ".pbrt" || name.find(".v4.") != std::string::npos) continue;
        const std::string v3 = e.path().string();
        const std::string v4 =
            (e.path().parent_path() / (e.path().stem().string() + ".v4.pbrt")).string();
        ASSERT_TRUE(fs::exists(v4)) << v4;
        EXPECT_EQ(RulesOf(v3), 3) << name;
        EXPECT_EQ(RulesOf(v4), 4) << name;
        const BuildSettings opts = SizedSettings(48, 36, 16);
        const Rendered a = RenderSceneFile(v3, opts), b = RenderSceneFile(v4, opts);
        EXPECT_GT(MeanValue(a.image), 0.05) << name;
        EXPECT_EQ(MaxAbsDiff(a.image, b.image), 0) << name;
        EXPECT_TRUE(a.warnings.empty()) << name << ": " << a.warnings.front().message;
        EXPECT_TRUE(b.warnings.empty()) << name << ": " << b.warnings.front().message;
        ++pairs;
    }
    EXPECT_EQ(pairs, 2);
}

}  // namespace
}  // namespace prism
