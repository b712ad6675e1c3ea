// The lights of render/light_list.inc, created by their own Create (render/light.h): the
// registry, and what the scene assembly does with a LightSource it lacks.
#include <gtest/gtest.h>

#include <algorithm>

#include "assembly/build_scene.h"
#include "render/infinite_light.h"
#include "scene/load_scene.h"
#include "test_util.h"

namespace prism {
namespace {

TEST(Light, TheRegistryNamesEachLightOnce) {
    const std::vector<std::string> &names = LightNames();
    for (const char *n : {"point", "spot", "distant", "infinite"})
        EXPECT_EQ(std::count(names.begin(), names.end(), n), 1) << n;
    EXPECT_EQ(names.size(), 4u);
}

TEST(Light, EachLightSourceIsItsClassAndAnUnknownOneIsIgnoredWithAWarning) {
    Diagnostics diag(false);
    SceneDescription desc =
        LoadScene(test::WriteTestFile(test::ScratchDir("light") / "l.pbrt",
                                      "WorldBegin\nLightSource \"point\" \"rgb I\" [1 2 3]\n"
                                      "LightSource \"spot\"\nLightSource \"distant\"\n"
                                      "LightSource \"infinite\" \"integer nsamples\" 4\n"
                                      "LightSource \"goniometric\"\nLightSource \"goniometric\"\n"
                                      "Shape \"sphere\"\nWorldEnd\n"),
                  diag);
    BuildSettings s;
    s.resolution = Vec2i(4, 4);
    RenderScene scene = BuildRenderScene(desc, s, diag);
    ASSERT_EQ(scene.lights.size(), 4u);
    const char *want[] = {"point", "spot", "distant", "infinite"};
    for (size_t i = 0; i < 4; ++i) EXPECT_STREQ(scene.lights[i]->Name(), want[i]);
    EXPECT_EQ(scene.lights[3]->NumSamples(), 4);
    EXPECT_TRUE(scene.features.environment);
    int warned = 0;
    for (const Warning &w : diag.Warnings())
        warned += w.loc.line == 6 &&
                  w.message.find("\"goniometric\" is not supported") != std::string::npos;
    EXPECT_EQ(warned, 1);  // once per type
}

}  // namespace
}  // namespace prism
