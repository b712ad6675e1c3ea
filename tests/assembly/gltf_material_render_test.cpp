// The glTF material in whole renders: a metallic 1 / roughness 0 sphere renders as pbrt's
// "mirror" of the same colour (up to the Schlick rise toward its rim), and a material's own
// emission is seen by camera rays.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "assembly/build_scene.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/render_text.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

Image RenderText(const std::string &name, const std::string &text, Diagnostics &diag) {
    Rendered r = RenderSceneText("prism_gltf_render", name, text);
    for (const Warning &w : r.warnings) diag.Warn(w.loc, w.message);
    return r.image;
}

std::string SphereScene(const std::string &material) {
    return R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 30
Film "image" "integer xresolution" 64 "integer yresolution" 64
Sampler "stratified" "integer xsamples" 1 "integer ysamples" 1 "bool jitter" false
Integrator "whitted"
WorldBegin
LightSource "distant" "point from" [0 1 1] "point to" [0 0 0] "rgb L" [2 2 2]
AttributeBegin
  Material "matte" "rgb Kd" [0.8 0.8 0.8]
  Texture "checks" "spectrum" "checkerboard" "float uscale" 8 "float vscale" 8
    "rgb tex1" [0.9 0.1 0.1] "rgb tex2" [0.1 0.1 0.9]
  Material "matte" "texture Kd" "checks"
  Translate 0 0 -3
  Shape "trianglemesh" "integer indices" [0 1 2 0 2 3]
    "point P" [-6 -6 0  6 -6 0  6 6 0  -6 6 0] "float uv" [0 0 1 0 1 1 0 1]
AttributeEnd
AttributeBegin
  Rotate -90 1 0 0
  Material "matte" "rgb Kd" [0.5 0.8 0.3]
  Shape "disk" "float radius" 20 "float height" -1.2
AttributeEnd
)" + material +
           R"(
Shape "sphere" "float radius" 1
WorldEnd
)";
}

TEST(GltfMaterialRender, PolishedMetalSphereIsAMirror) {
    Diagnostics d1, d2;
    Image gltf = RenderText(
        "gltf_mirror",
        SphereScene(
            R"(Material "gltf" "rgb basecolor" [0.9 0.7 0.4] "float metallic" 1 "float roughness" 0)"),
        d1);
    Image mirror =
        RenderText("pbrt_mirror", SphereScene(R"(Material "mirror" "rgb Kr" [0.9 0.7 0.4])"), d2);
    EXPECT_TRUE(d1.Warnings().empty()) << d1.Warnings()[0].ToString();
    ASSERT_EQ(gltf.width, mirror.width);
    // Inside the sphere's central disc (cos θ > 0.8: Schlick adds < 3e-4) the images agree;
    // toward the rim the glTF sphere is brighter, as Schlick's Fresnel rises to 1.
    double centralDiff = 0, centralSum = 0, rimGltf = 0, rimMirror = 0;
    int central = 0;
    for (int y = 0; y < gltf.height; ++y)
        for (int x = 0; x < gltf.width; ++x) {
            // The sphere covers a disc of radius 32 · tan(asin(1/5)) / tan(15°) ≈ 24 px.
            double dx = x + 0.5 - 32, dy = y + 0.5 - 32, r = std::sqrt(dx * dx + dy * dy);
            RGB a = gltf.GetRGB(x, y), b = mirror.GetRGB(x, y);
            if (r < 12) {
                for (int c = 0; c < 3; ++c) {
                    centralDiff += std::abs(a[c] - b[c]);
                    centralSum += b[c];
                }
                ++central;
            } else if (r > 21.5 && r < 23.5) {
                rimGltf += a.Luminance();
                rimMirror += b.Luminance();
            }
        }
    ASSERT_GT(central, 50);
    ASSERT_GT(centralSum, 0);
    EXPECT_LT(centralDiff / centralSum, 0.01);
    EXPECT_GE(rimGltf, rimMirror * 0.999);
}

TEST(GltfMaterialRender, EmissionIsSeenByCameraRays) {
    Diagnostics diag;
    Image img = RenderText("gltf_emissive", R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 10
Film "image" "integer xresolution" 8 "integer yresolution" 8
Integrator "whitted"
WorldBegin
Material "gltf" "rgb basecolor" [0 0 0] "float metallic" 0 "float specular" 0
  "rgb emissive" [0.5 1 2]
Shape "sphere" "float radius" 1
WorldEnd
)",
                           diag);
    RGB c = img.GetRGB(4, 4);
    EXPECT_NEAR(c.r, 0.5f, 1e-4f);
    EXPECT_NEAR(c.g, 1.f, 1e-4f);
    EXPECT_NEAR(c.b, 2.f, 1e-4f);
}

}  // namespace
}  // namespace prism
