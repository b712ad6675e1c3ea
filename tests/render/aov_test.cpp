// The AOVs come from the render itself (render/aov.h AovFrame, filled by the tile driver): the
// variance layer is the sample variance of the beauty's own samples, whatever the integrator,
// and direct + indirect is the beauty.
#include "render/aov.h"

#include <gtest/gtest.h>

#include <cmath>

#include "assembly/build_scene.h"
#include "render/light_sampling.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

// A box lit by an area light: direct light, and indirect light between the walls.
const char *kRoom = R"(LookAt 0 1 -3.5  0 1 0  0 1 0
Camera "perspective" "float fov" [ 50 ]
Integrator "path" "integer maxdepth" [ 4 ]
WorldBegin
AttributeBegin
AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]
Translate 0 1.9 0
Rotate 90 1 0 0
Shape "disk" "float radius" [ 0.4 ]
AttributeEnd
Material "matte" "rgb Kd" [ 0.7 0.6 0.5 ]
Shape "trianglemesh" "integer indices" [0 1 2 0 2 3  4 5 6 4 6 7  8 9 10 8 10 11]
  "point P" [-1 0 -1  1 0 -1  1 0 1  -1 0 1
             -1 0 1  1 0 1  1 2 1  -1 2 1
             -1 0 -1  -1 0 1  -1 2 1  -1 2 -1]
Material "matte" "rgb Kd" [ 0.2 0.7 0.2 ]
Shape "sphere" "float radius" [ 0.35 ]
WorldEnd
)";

// Each test and integrator writes a file of its own (ctest runs tests in parallel).
RenderScene BuildRoom(const std::string &test, const std::string &integrator, int spp) {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(
        WriteTestFile(ScratchDir("aov") / (test + "-" + integrator + ".pbrt"), kRoom), diag);
    BuildSettings s;
    s.resolution = Vec2i(12, 10);
    s.spp = spp;
    s.integrator = integrator;
    return BuildRenderScene(desc, s, diag);
}

TEST(Aov, VarianceIsThatOfTheBeautysOwnSamples) {
    for (const char *integrator : {"path", "volpath", "directlighting", "whitted"}) {
        SCOPED_TRACE(integrator);
        const int spp = 8;
        RenderScene scene = BuildRoom("variance", integrator, spp);
        AovFrame frame(scene, {Aov::Variance}, {});
        RenderOptions options;
        options.sampler = scene.sampler;
        options.aovs = &frame;
        const Image beauty = Render(scene, options, nullptr);
        const std::vector<AovLayer> layers = frame.Layers();
        ASSERT_EQ(layers.size(), 1u);
        const std::vector<float> &variance = layers[0].pixels;
        // Each pixel's samples again, one by one through the integrator's Li.
        const CameraSampler camera(scene, scene.sampler);
        double nonzero = 0;
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 12; ++x) {
                const CameraSampler::Seeds seeds = camera.PixelSeeds(x, y);
                double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
                for (uint32_t s = 0; s < uint32_t(spp); ++s) {
                    const CameraSample cs = camera.Sample(x, y, s, seeds);
                    const Ray ray = camera.GenerateRay(cs);
                    ASSERT_EQ(scene.sampler.seed, 0u);
                    const PixelSamples ps =
                        PixelSamplesOf(scene.sampler, x, y, s, uint32_t(spp), scene.trace);
                    RayCounters rc;
                    const RGB L = scene.integrator->Li(scene, ray, ps, rc, nullptr);
                    const double v[3] = {L.r, L.g, L.b};
                    for (int c = 0; c < 3; ++c) sum[c] += v[c], sum2[c] += v[c] * v[c];
                }
                for (int c = 0; c < 3; ++c) {
                    const double mean = sum[c] / spp;
                    const double var = (sum2[c] - spp * mean * mean) / (spp - 1);
                    const float got = variance[(size_t(y) * 12 + size_t(x)) * 3 + size_t(c)];
                    EXPECT_NEAR(got, var, 1e-5 * (1 + var)) << x << "," << y << " " << c;
                    // The box-filtered beauty is the same samples' mean.
                    EXPECT_NEAR(beauty.GetRGB(x, y)[c], mean, 1e-5 * (1 + mean));
                    nonzero += var > 0;
                }
            }
        EXPECT_GT(nonzero, 100);  // the samples differ: the comparison is not of zeros
    }
}

TEST(Aov, DirectPlusIndirectIsTheBeautyUnderThePathIntegrators) {
    for (const char *integrator : {"path", "volpath", "directlighting", "whitted"}) {
        SCOPED_TRACE(integrator);
        RenderScene scene = BuildRoom("split", integrator, 4);
        ASSERT_TRUE(scene.integrator->Traits().directAov);
        AovFrame frame(scene, {Aov::Direct, Aov::Indirect}, {});
        RenderOptions options;
        options.sampler = scene.sampler;
        options.aovs = &frame;
        const Image beauty = Render(scene, options, nullptr);
        const std::vector<AovLayer> layers = frame.Layers();
        ASSERT_EQ(layers.size(), 2u);
        double direct = 0, indirect = 0;
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 12; ++x)
                for (int c = 0; c < 3; ++c) {
                    const size_t i = (size_t(y) * 12 + size_t(x)) * 3 + size_t(c);
                    const float b = beauty.GetRGB(x, y)[c];
                    EXPECT_NEAR(layers[0].pixels[i] + layers[1].pixels[i], b, 1e-4 * (1 + b));
                    direct += layers[0].pixels[i];
                    indirect += layers[1].pixels[i];
                }
        EXPECT_GT(direct, 0);
        // Light between the walls is indirect for path; directlighting and Whitted recurse only
        // on delta lobes, which the matte room lacks.
        if (std::string(integrator).find("path") != std::string::npos)
            EXPECT_GT(indirect, 0.05 * direct);
        else
            EXPECT_NEAR(indirect, 0, 1e-6 * direct);
    }
}

}  // namespace
}  // namespace prism
