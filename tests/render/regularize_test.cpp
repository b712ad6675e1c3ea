// pbrt-v4's "regularize" of path and volpath (BSDF::Regularize, render/path_vertex.h): which
// lobes it roughens and by how much, and that it lets light samples reach a caustic of a small
// light seen through smooth glass, after the first non-specular bounce only.
#include <gtest/gtest.h>

#include "render/bsdf.h"
#include "support/image_stats.h"
#include "support/render_text.h"

namespace prism {
namespace {

using namespace test;

BSDF WithPart(const BxDFLobes &lobes) {
    BSDF b;
    b.SetFrame(Vec3f(0, 0, 1), Vec3f(1, 0, 0), Vec3f(0, 0, 1));
    b.AddPart(RGB(1), lobes);
    return b;
}

TEST(Regularize, RoughensDielectricAndConductorLobesOnly) {
    // Smooth glass: its delta lobes become rough, alpha 0.1, and then glossy lobes.
    BxDFLobes glass;
    glass.kr = glass.kt = RGB(1);
    glass.specularFresnel.kind = FresnelKind::Dielectric;
    glass.eta = 1.5f;
    BSDF b = WithPart(glass);
    b.Regularize();
    EXPECT_FLOAT_EQ(b.Part(0).roughAlphaX, 0.1f);
    EXPECT_FLOAT_EQ(b.Part(0).roughAlphaY, 0.1f);
    EXPECT_TRUE(b.MakeRoughSpecularGlossy());
    EXPECT_FLOAT_EQ(b.Part(0).alphaX, 0.1f);
    EXPECT_TRUE(b.Part(0).kr.IsBlack());
    EXPECT_TRUE(b.HasNonSpecular());

    // A rough conductor: alpha doubled within [0.1, 0.3], per axis; 0.3 and above unchanged.
    BxDFLobes metal;
    metal.ks = RGB(1);
    metal.glossyFresnel.kind = FresnelKind::Conductor;
    for (auto [before, after] :
         {std::pair{0.01f, 0.1f}, {0.08f, 0.16f}, {0.2f, 0.3f}, {0.3f, 0.3f}, {0.7f, 0.7f}}) {
        metal.alphaX = before;
        metal.alphaY = 0.5f;
        BSDF m = WithPart(metal);
        m.Regularize();
        EXPECT_FLOAT_EQ(m.Part(0).alphaX, after) << before;
        EXPECT_FLOAT_EQ(m.Part(0).alphaY, 0.5f);
    }

    // Unchanged: a mirror (no Fresnel), a thin dielectric, index-matched glass, a Lambertian
    // lobe, and a glTF (Schlick) glossy lobe.
    BxDFLobes mirror;
    mirror.kr = RGB(1);
    BxDFLobes thin = glass;
    thin.specularFresnel.kind = FresnelKind::ThinDielectric;
    BxDFLobes matched = glass;
    matched.eta = 1;
    BxDFLobes gltf;
    gltf.ks = RGB(1);
    gltf.alphaX = gltf.alphaY = 0.05f;
    gltf.glossyFresnel.kind = FresnelKind::Schlick;
    BxDFLobes matte;
    matte.kd = RGB(0.5f);
    for (const BxDFLobes &l : {mirror, thin, matched, gltf, matte}) {
        BSDF u = WithPart(l);
        u.Regularize();
        EXPECT_EQ(u.Part(0).roughAlphaX, 0.f);
        EXPECT_EQ(u.Part(0).alphaX, l.alphaX);
    }

    // pbrt-v4's layered lobe: the coat and a conductor base.
    BxDFLobes coated;
    coated.layered.base = LayeredLobe::Base::Conductor;
    coated.layered.baseAlphaX = coated.layered.baseAlphaY = 0.02f;
    BSDF c = WithPart(coated);
    c.Regularize();
    EXPECT_FLOAT_EQ(c.Part(0).layered.coatAlphaX, 0.1f);
    EXPECT_FLOAT_EQ(c.Part(0).layered.baseAlphaY, 0.1f);
}

// A spot light straight above a smooth glass sphere over a diffuse floor, seen from above: the
// caustic under the sphere is light no path finds unless the glass is roughened after the
// floor's diffuse bounce.
std::string CausticScene(const std::string &integrator, bool regularize, int maxdepth) {
    return "LookAt 0 6 0  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" 40\n"
           "Sampler \"independent\"\nIntegrator \"" +
           integrator + "\" \"integer maxdepth\" " + std::to_string(maxdepth) +
           " \"bool regularize\" " + (regularize ? "true" : "false") +
           "\nWorldBegin\n"
           "LightSource \"spot\" \"point3 from\" [0 5 0] \"point3 to\" [0 0 0] "
           "\"float coneangle\" 30 \"rgb I\" [20 20 20]\n"
           "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
           "Shape \"trianglemesh\" \"point3 P\" [-5 0 -5 5 0 -5 5 0 5 -5 0 5] "
           "\"integer indices\" [0 1 2 0 2 3]\n"
           "AttributeBegin\nMaterial \"dielectric\" \"float eta\" 1.5\nTranslate 1.2 1 0\n"
           "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n";
}

TEST(Regularize, FindsTheCausticAfterADiffuseBounceOnly) {
    for (const char *integrator : {"path", "volpath"}) {
        SCOPED_TRACE(integrator);
        const BuildSettings s = SizedSettings(48, 48, 64);
        auto render = [&](bool regularize, int maxdepth) {
            const Rendered r = RenderSceneText("regularize", regularize ? "on.pbrt" : "off.pbrt",
                                               CausticScene(integrator, regularize, maxdepth), s);
            EXPECT_TRUE(r.warnings.empty()) << r.warnings[0].ToString();
            return r.image;
        };
        const double off = MeanValue(render(false, 5)), on = MeanValue(render(true, 5));
        EXPECT_GT(on, off * 1.02) << "the caustic adds light";
        EXPECT_LT(on, off * 1.5);
        // With one bounce every path ends at the first surface it meets, where nothing has been
        // roughened yet: the glass the camera sees is smooth either way.
        EXPECT_EQ(MaxAbsDiff(render(true, 1), render(false, 1)), 0.0);
    }
}

// bdpt finds the caustic without regularization (its light paths reach the floor through the
// glass); regularized, the roughened glass the camera subpath meets after the floor is also
// reached by light samples, whose MIS weights assume the smooth glass of the light subpath:
// the image gets brighter, as pbrt-v4's does (its probe regularize-bdpt: 1.5%; this small
// scene's caustic much more). Before a non-specular bounce nothing changes, on either subpath.
// mlt reads the same flag for the same walks.
TEST(Regularize, BdptRegularizesEachSubpathAfterItsFirstDiffuseBounce) {
    const BuildSettings s = SizedSettings(40, 40, 32);
    auto render = [&](const char *integrator, bool regularize, int maxdepth) {
        const Rendered r = RenderSceneText("regularize", regularize ? "bon.pbrt" : "boff.pbrt",
                                           CausticScene(integrator, regularize, maxdepth), s);
        EXPECT_TRUE(r.warnings.empty()) << r.warnings[0].ToString();
        return r.image;
    };
    const Image on = render("bdpt", true, 5), off = render("bdpt", false, 5);
    EXPECT_GT(MeanValue(on), MeanValue(off) * 1.01);
    EXPECT_EQ(MaxAbsDiff(render("bdpt", true, 1), render("bdpt", false, 1)), 0.0);
    const Built mlt =
        BuildSceneFile(WriteSceneText("regularize", "mlt", CausticScene("mlt", true, 5)));
    for (const Warning &w : mlt.warnings)  // (it warns that it draws its own samples)
        EXPECT_EQ(w.ToString().find("\"regularize\""), std::string::npos) << w.ToString();
}

}  // namespace
}  // namespace prism
