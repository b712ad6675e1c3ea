// Metropolis light transport (Integrator "mlt", render/mlt_integrator.h): a furnace with a
// closed form, agreement with Prism's path tracer on a diffuse room, the same image for any
// thread count, and parameters out of range refused.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <string>

#include "assembly/build_scene.h"
#include "core/error.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace prism {
namespace {

using namespace test;

RenderScene BuildText(const std::string &name, const std::string &text) {
    return BuildSceneText("mlt", name, text);
}

std::string Mlt(int mutations, int bootstrap = 4096, int chains = 64, int maxDepth = 5) {
    return "Integrator \"mlt\" \"integer maxdepth\" [" + std::to_string(maxDepth) +
           "] \"integer mutationsperpixel\" [" + std::to_string(mutations) +
           "] \"integer bootstrapsamples\" [" + std::to_string(bootstrap) +
           "] \"integer chains\" [" + std::to_string(chains) + "]";
}

TEST(Mlt, FurnaceIsTheGeometricSeries) {
    // The camera inside a closed sphere of albedo 0.6 whose inside emits 1: 1 + 0.6 + 0.36 at
    // maxdepth 2.
    const std::string text =
        "Film \"image\" \"integer xresolution\" [16] \"integer yresolution\" [12]\n" +
        Mlt(256, 16384, 32, 2) +
        "\nCamera \"perspective\" \"float fov\" [70]\nWorldBegin\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"bool twosided\" true\n"
        "Material \"matte\" \"rgb Kd\" [0.6 0.6 0.6]\nShape \"sphere\" \"float radius\" [3]\n"
        "AttributeEnd\n";
    RenderScene scene = BuildText("furnace", text);
    EXPECT_STREQ(scene.IntegratorName(), "mlt");
    EXPECT_NEAR(MeanValue(RenderWithSeed(scene, 0)), 1.96, 0.02 * 1.96);
}

// A diffuse box with a matte sphere in it, lit by a small spherical area light.
std::string Room(const std::string &integrator, int spp) {
    return "LookAt 1.6 1.4 1.8  -0.8 1.2 -1.6  0 1 0\nCamera \"perspective\" \"float fov\" [70]\n"
           "Film \"image\" \"integer xresolution\" [32] \"integer yresolution\" [24]\n"
           "Sampler \"random\" \"integer pixelsamples\" [" +
           std::to_string(spp) + "]\n" + integrator +
           "\nWorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [4 4 4]\n"
           "Translate 0 3.2 0\nShape \"sphere\" \"float radius\" [0.3]\nAttributeEnd\n"
           "Material \"matte\" \"rgb Kd\" [0.7 0.7 0.7]\n" +
           kClosedRoom +
           "AttributeBegin\nMaterial \"matte\" \"rgb Kd\" [0.2 0.3 0.6]\n"
           "Translate -0.6 0.6 -0.9\nShape \"sphere\" \"float radius\" [0.6]\nAttributeEnd\n";
}

TEST(Mlt, AgreesWithPathOnADiffuseRoom) {
    // The means agree (within 0.2% when written), and the image converges on the path
    // tracer's: four times the mutations, about half the distance (0.25, then 0.14).
    RenderScene mlt64 = BuildText("room_mlt64", Room(Mlt(64, 32768), 1));
    RenderScene mlt256 = BuildText("room_mlt256", Room(Mlt(256, 32768), 1));
    RenderScene path = BuildText("room_path", Room("Integrator \"path\"", 256));
    const Image m64 = RenderWithSeed(mlt64, 0), m256 = RenderWithSeed(mlt256, 0);
    const Image p = RenderWithSeed(path, 0);
    EXPECT_NEAR(MeanValue(m64), MeanValue(p), 0.02 * MeanValue(p));
    EXPECT_NEAR(MeanValue(m256), MeanValue(p), 0.02 * MeanValue(p));
    const double d64 = RelL1(m64, p), d256 = RelL1(m256, p);
    EXPECT_LT(d64, 0.35);
    EXPECT_LT(d256, 0.7 * d64) << "64: " << d64 << ", 256: " << d256;
}

// A light sample (strategy s = 1) needs no light subpath: the paths whose light subpath a
// projection light does not emit (a direction of its cone outside its frustum) still get
// their light sample, as bdpt's do (otherwise the image was 8.7% dark on the projection
// probe).
TEST(Mlt, LightSamplesNeedNoLightSubpath) {
    auto room = [](const std::string &integrator, int spp) {
        return "LookAt 1.6 1.4 1.8  -0.8 1.2 -1.6  0 1 0\nCamera \"perspective\" \"float "
               "fov\" [70]\nFilm \"image\" \"integer xresolution\" [32] \"integer "
               "yresolution\" [24]\nSampler \"random\" \"integer pixelsamples\" [" +
               std::to_string(spp) + "]\n" + integrator +
               "\nWorldBegin\nAttributeBegin\nTranslate 0 3.9 0\nRotate 90 1 0 0\n"
               "LightSource \"projection\" \"rgb I\" [20 20 20] \"float fov\" [50]\n"
               "AttributeEnd\nMaterial \"matte\" \"rgb Kd\" [0.7 0.7 0.7]\n" +
               std::string(kClosedRoom);
    };
    RenderScene mlt = BuildText("projection_mlt", room(Mlt(64, 32768), 1));
    RenderScene path = BuildText("projection_path", room("Integrator \"path\"", 256));
    const double m = MeanValue(RenderWithSeed(mlt, 0)), p = MeanValue(RenderWithSeed(path, 0));
    EXPECT_NEAR(m, p, 0.03 * p);
}

TEST(Mlt, SameImageForAnyThreadCount) {
    RenderScene scene = BuildText("threads", Room(Mlt(8, 1024, 16), 1));
    Image one = RenderOnThreads(scene, 1), two = RenderOnThreads(scene, 2);
    EXPECT_TRUE(one.pixels == two.pixels);
    EXPECT_GT(MeanValue(one), 0);
    // Another seed, another image.
    EXPECT_FALSE(RenderWithSeed(scene, 1).pixels == one.pixels);
}

// --spp (BuildSettings::spp) is mlt's mutations per pixel: it wins over mutationsperpixel.
TEST(Mlt, SppSetsTheMutationsPerPixel) {
    BuildSettings opts;
    opts.spp = 3;
    RenderScene scene = BuildSceneText("mlt", "spp", Room(Mlt(8, 1024, 16), 1), opts);
    RenderStats stats;
    Render(scene, &stats);
    EXPECT_EQ(stats.spp, 3);
}

TEST(Mlt, ParametersOutOfRangeAreRefused) {
    for (const char *bad : {"\"integer chains\" [0]", "\"integer mutationsperpixel\" [-1]",
                            "\"integer bootstrapsamples\" [0]", "\"float sigma\" [0]",
                            "\"float largestepprobability\" [1.5]"}) {
        const std::string text = std::string("Integrator \"mlt\" ") + bad +
                                 "\nWorldBegin\nLightSource \"point\"\nShape \"sphere\"\n";
        EXPECT_THROW(BuildText("bad", text), SceneError) << bad;
    }
}

}  // namespace
}  // namespace prism
