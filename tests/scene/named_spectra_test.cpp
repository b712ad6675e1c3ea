// pbrt-v4's named spectra as RGB (scene/named_spectra.h).
#include "scene/named_spectra.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "scene/pbrt_parser.h"

namespace prism {
namespace {

// Reflectance at normal incidence of a conductor of index eta + i k.
float F0(float eta, float k) {
    return ((eta - 1) * (eta - 1) + k * k) / ((eta + 1) * (eta + 1) + k * k);
}
RGB F0(const RGB &eta, const RGB &k) { return {F0(eta.r, k.r), F0(eta.g, k.g), F0(eta.b, k.b)}; }
RGB Named(const char *name) {
    std::optional<RGB> c = NamedSpectrumRGB(name);
    EXPECT_TRUE(c) << name;
    return c.value_or(RGB(0.f));
}

TEST(NamedSpectra, EveryBuiltInNameResolvesAndIsNamed) {
    const std::vector<std::string> names = BuiltInSpectrumNames();
    EXPECT_EQ(names.size(), 10u + 10u + 16u);
    for (const std::string &n : names) {
        SCOPED_TRACE(n);
        EXPECT_TRUE(IsNamedSpectrum(n));
        const RGB c = Named(n.c_str());
        EXPECT_GT(c.r, 0.f);
        EXPECT_GT(c.g, 0.f);
        EXPECT_GT(c.b, 0.f);
    }
}

// Measured colours: gold and copper reflect red more than blue, gold more green than copper,
// silver and aluminium reflect nearly everything and nearly neutrally.
TEST(NamedSpectra, MetalsHaveTheirColours) {
    const RGB au = F0(Named("metal-Au-eta"), Named("metal-Au-k"));
    const RGB cu = F0(Named("metal-Cu-eta"), Named("metal-Cu-k"));
    const RGB ag = F0(Named("metal-Ag-eta"), Named("metal-Ag-k"));
    const RGB al = F0(Named("metal-Al-eta"), Named("metal-Al-k"));
    const RGB brass = F0(Named("metal-CuZn-eta"), Named("metal-CuZn-k"));
    EXPECT_GT(au.r, 0.9f);
    EXPECT_GT(au.r, au.g);
    EXPECT_GT(au.g, au.b);
    EXPECT_LT(au.b, 0.5f);
    EXPECT_GT(cu.r, cu.g);
    EXPECT_GT(cu.g, cu.b);
    EXPECT_GT(au.g, cu.g);
    EXPECT_GT(brass.r, brass.b);
    for (const RGB &c : {ag, al}) {
        EXPECT_GT(c.r, 0.85f);
        EXPECT_GT(c.b, 0.85f);
        EXPECT_LT(std::abs(c.r - c.b), 0.08f);
    }
}

// A glass's index rises toward the blue (normal dispersion); its luminance-weighted mean, the
// index near 555 nm, lies between the catalogue's n_d (587.6 nm) and n_F (486.1 nm).
TEST(NamedSpectra, GlassesDisperseAroundTheirCatalogueIndex) {
    struct Glass {
        const char *name;
        float nd, nF;
    };
    const Glass glasses[] = {{"glass-BK7", 1.51680f, 1.52238f},
                             {"glass-BAF10", 1.67003f, 1.68000f},
                             {"glass-F11", 1.78472f, 1.80651f}};
    for (const Glass &g : glasses) {
        SCOPED_TRACE(g.name);
        const RGB n = Named(g.name);
        EXPECT_LT(n.r, n.g);
        EXPECT_LT(n.g, n.b);
        EXPECT_GT(n.Luminance(), g.nd);
        EXPECT_LT(n.Luminance(), g.nF);
    }
    const RGB sf11 = Named("glass-SF11"), f11 = Named("glass-F11");
    EXPECT_EQ(sf11.g, f11.g);
}

// D65 is sRGB's white; illuminant A is a 2856 K blackbody's reddish white; each at luminance 1.
TEST(NamedSpectra, IlluminantsAreTheirChromaticityAtLuminanceOne) {
    const RGB d65 = Named("stdillum-D65");
    EXPECT_NEAR(d65.r, 1.f, 2e-3f);
    EXPECT_NEAR(d65.g, 1.f, 2e-3f);
    EXPECT_NEAR(d65.b, 1.f, 2e-3f);
    const RGB a = Named("stdillum-A");
    EXPECT_NEAR(a.Luminance(), 1.f, 2e-3f);
    EXPECT_GT(a.r, a.g);
    EXPECT_GT(a.g, a.b);
    EXPECT_LT(a.b, 0.5f);
}

TEST(NamedSpectra, NamesWithoutDataAreNamedButNotBuiltIn) {
    std::string why;
    EXPECT_TRUE(IsNamedSpectrum("metal-TiO2-eta"));
    EXPECT_FALSE(NamedSpectrumRGB("metal-TiO2-eta", &why));
    EXPECT_NE(why.find("not built into Prism"), std::string::npos) << why;
    EXPECT_FALSE(IsNamedSpectrum("metal-Xx-eta"));
    EXPECT_FALSE(IsNamedSpectrum("Cu.eta.spd"));
}

// A "spectrum" parameter naming one is resolved before any file is looked for; one pbrt-v4
// has but Prism does not build in is a warning at the parameter and a constant 1.
TEST(NamedSpectra, AParameterNamingOneUsesIt) {
    Diagnostics diag(false);
    const SceneDescription d = ParsePbrtString(
        "WorldBegin\nMaterial \"conductor\" \"spectrum eta\" \"metal-Au-eta\"\n"
        "  \"spectrum k\" \"metal-MgO-k\"\n",
        "n.pbrt", diag);
    const RGB eta = d.materials.at(0).params.GetRGB("eta", RGB(0.f));
    EXPECT_EQ(eta.r, Named("metal-Au-eta").r);
    EXPECT_EQ(d.materials.at(0).params.GetRGB("k", RGB(0.f)).g, 1.f);
    ASSERT_EQ(diag.Warnings().size(), 1u);
    EXPECT_NE(diag.Warnings()[0].ToString().find("n.pbrt:3:3"), std::string::npos)
        << diag.Warnings()[0].ToString();
}

}  // namespace
}  // namespace prism
