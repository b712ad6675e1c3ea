// MakeNamedMedium directives → render/ media (pbrt-v3 api.cpp MakeMedium: names, defaults and
// the "preset" table), and the media effect of shapes and the camera.
#include "assembly/media.h"

#include <algorithm>
#include <cmath>

#include "assembly/scene_effects.h"

namespace prism {

namespace {

// pbrt-v3's GetMediumScatteringProperties table (core/medium.cpp): σ's (reduced scattering,
// used as σs) and σa in mm^-1, from Jensen et al. 2001, "A Practical Model for Subsurface Light
// Transport", and Narasimhan et al. 2006, "Acquiring Scattering Properties of Participating
// Media by Dilution". Prism includes the measured solids and the milks, coffees and juices
// most used in scenes (not every entry of pbrt's table: docs/INTEGRATORS.md lists them).
struct MediumPreset {
    const char *name;
    RGB sigmaPrimeS, sigmaA;
};
const MediumPreset Presets[] = {
    {"Apple", {2.29f, 2.39f, 1.97f}, {0.0030f, 0.0034f, 0.046f}},
    {"Chicken1", {0.15f, 0.21f, 0.38f}, {0.015f, 0.077f, 0.19f}},
    {"Chicken2", {0.19f, 0.25f, 0.32f}, {0.018f, 0.088f, 0.20f}},
    {"Cream", {7.38f, 5.47f, 3.15f}, {0.0002f, 0.0028f, 0.0163f}},
    {"Ketchup", {0.18f, 0.07f, 0.03f}, {0.061f, 0.97f, 1.45f}},
    {"Marble", {2.19f, 2.62f, 3.00f}, {0.0021f, 0.0041f, 0.0071f}},
    {"Potato", {0.68f, 0.70f, 0.55f}, {0.0024f, 0.0090f, 0.12f}},
    {"Skimmilk", {0.70f, 1.22f, 1.90f}, {0.0014f, 0.0025f, 0.0142f}},
    {"Skin1", {0.74f, 0.88f, 1.01f}, {0.032f, 0.17f, 0.48f}},
    {"Skin2", {1.09f, 1.59f, 1.79f}, {0.013f, 0.070f, 0.145f}},
    {"Spectralon", {11.6f, 20.4f, 14.9f}, {0.00f, 0.00f, 0.00f}},
    {"Wholemilk", {2.55f, 3.21f, 3.77f}, {0.0011f, 0.0024f, 0.014f}},
    {"Lowfat Milk", {0.89187f, 1.5136f, 2.532f}, {0.002875f, 0.00575f, 0.0115f}},
    {"Reduced Milk", {2.4858f, 3.1669f, 4.5214f}, {0.0025556f, 0.0051111f, 0.012778f}},
    {"Regular Milk", {4.5513f, 5.8294f, 7.136f}, {0.0015333f, 0.0046f, 0.019933f}},
    {"Espresso", {0.72378f, 0.84557f, 1.0247f}, {4.7984f, 6.5751f, 8.8493f}},
    {"Mint Mocha Coffee", {0.31602f, 0.38538f, 0.48131f}, {3.772f, 5.8228f, 7.82f}},
    {"Lowfat Soy Milk", {0.30576f, 0.34233f, 0.61664f}, {0.0014375f, 0.0071875f, 0.035937f}},
    {"Regular Soy Milk", {0.59223f, 0.73866f, 1.4693f}, {0.0019167f, 0.0095833f, 0.065167f}},
    {"Lowfat Chocolate Milk", {0.64925f, 0.83916f, 1.1057f}, {0.0115f, 0.0368f, 0.1564f}},
    {"Regular Chocolate Milk", {1.4585f, 2.1289f, 2.9527f}, {0.010063f, 0.043125f, 0.14375f}},
    {"Coke", {8.9053e-05f, 8.372e-05f, 0.f}, {0.10014f, 0.16503f, 0.2468f}},
    {"Pepsi", {6.1697e-05f, 4.2564e-05f, 0.f}, {0.091641f, 0.14158f, 0.20729f}},
    {"Sprite", {6.0306e-06f, 6.4139e-06f, 6.5504e-06f}, {0.001886f, 0.0018308f, 0.0020025f}},
    {"Merlot", {2.1129e-05f, 0.f, 0.f}, {0.11632f, 0.25191f, 0.29434f}},
    {"Apple Juice", {0.00013612f, 0.00015836f, 0.000227f}, {0.012957f, 0.023741f, 0.052184f}},
    {"Grape Juice", {5.382e-05f, 0.f, 0.f}, {0.10404f, 0.23958f, 0.29325f}},
    {"Shampoo", {0.0007176f, 0.0008303f, 0.0009016f}, {0.014107f, 0.045693f, 0.061717f}},
    {"Pacific Ocean Surface Water",
     {0.0001764f, 0.00032095f, 0.00019617f},
     {0.031845f, 0.031324f, 0.030147f}},
};

// pbrt-v3's defaults when neither a preset nor sigma_a/sigma_s is given: whole milk.
constexpr RGB DefaultSigmaA(.0011f, .0024f, .014f), DefaultSigmaS(2.55f, 3.21f, 3.77f);

FileLoc ParamLoc(const MediumDesc &m, const char *name) {
    const Param *p = m.params.Find(name);
    return p ? p->loc : m.loc;
}

void CheckNonNegative(const MediumDesc &m, const char *name, const RGB &v) {
    if (v.r < 0 || v.g < 0 || v.b < 0 || !v.IsFinite())
        throw SceneError(ParamLoc(m, name), "medium " + Quote(m.name) + ": \"" + name +
                                                "\" must be finite and not negative");
}

// MakeNamedMedium "homogeneous", "heterogeneous" (pbrt-v3's). Parameters:
//   preset            string    ""     a measured medium of pbrt's table (its sigma_a and
//                                      sigma_s; unknown: whole milk, with a warning)
//   sigma_a, sigma_s  spectrum  .0011 .0024 .014, 2.55 3.21 3.77  absorption and scattering,
//                                      per unit length (pbrt-v3's whole milk)
//   scale             float     1      multiplies both, >= 0
//   g                 float     0      Henyey-Greenstein asymmetry, in (-1, 1)
//   stepsize          float     0      the single-scattering ray march's step (a Prism
//                                      extension; 0: an eighth of the mean free path)
//   nx, ny, nz        integer   1      heterogeneous: the density grid's size, 1 to 4096
//   density           float[]   —      heterogeneous: nx ny nz values, x fastest; required
//   p0, p1            point     0 0 0, 1 1 1  heterogeneous: the grid's box
std::unique_ptr<Medium> MakeMedium(BuildContext &ctx, const MediumDesc &m) {
    const ParamSet &ps = m.params;
    const std::string context = "medium " + Quote(m.name);
    RGB sigmaA = DefaultSigmaA, sigmaS = DefaultSigmaS;
    const std::string preset = ps.GetString("preset", "");
    if (!preset.empty()) {
        const MediumPreset *found = nullptr;
        for (const MediumPreset &p : Presets)
            if (preset == p.name) found = &p;
        if (found) {
            sigmaA = found->sigmaA;
            sigmaS = found->sigmaPrimeS;
        } else {
            ctx.diag.Warn(ParamLoc(m, "preset"), context + ": unknown preset " + Quote(preset) +
                                                     "; using the default (whole milk)");
        }
    }
    const float scale = ps.GetFloat("scale", 1.f);
    const float g = ps.GetFloat("g", 0.f);
    sigmaA = ps.GetRGB("sigma_a", sigmaA);
    sigmaS = ps.GetRGB("sigma_s", sigmaS);
    CheckNonNegative(m, "sigma_a", sigmaA);
    CheckNonNegative(m, "sigma_s", sigmaS);
    if (!(scale >= 0) || !std::isfinite(scale))
        throw SceneError(ParamLoc(m, "scale"), context +
                                                   ": \"scale\" must be finite and not "
                                                   "negative");
    if (!(std::abs(g) < 1))
        throw SceneError(ParamLoc(m, "g"), context + ": \"g\" must lie in (-1, 1)");
    sigmaA *= scale;
    sigmaS *= scale;
    // Prism extension: the ray-march step of single scattering (0: chosen per medium).
    const float step = ps.GetFloat("stepsize", 0.f);
    if (!(step >= 0) || !std::isfinite(step))
        throw SceneError(ParamLoc(m, "stepsize"), context + ": \"stepsize\" must be positive");
    std::unique_ptr<Medium> medium;
    if (m.type == "homogeneous") {
        medium = std::make_unique<HomogeneousMedium>(sigmaA, sigmaS, g, step);
    } else if (m.type == "heterogeneous") {
        const int nx = ps.GetInt("nx", 1), ny = ps.GetInt("ny", 1), nz = ps.GetInt("nz", 1);
        for (const char *n : {"nx", "ny", "nz"})
            if (ps.GetInt(n, 1) < 1 || ps.GetInt(n, 1) > 4096)
                throw SceneError(ParamLoc(m, n),
                                 context + ": \"" + n + "\" must be 1 to 4096 grid samples");
        if (!ps.Has("density"))
            throw SceneError(m.loc, context + ": a heterogeneous medium needs \"density\" values");
        std::vector<float> density = ps.GetFloats("density");
        const uint64_t want = uint64_t(nx) * uint64_t(ny) * uint64_t(nz);
        if (density.size() != want)
            throw SceneError(ParamLoc(m, "density"),
                             context + ": \"density\" has " + std::to_string(density.size()) +
                                 " values but nx*ny*nz is " + std::to_string(want));
        for (float d : density)
            if (!(d >= 0) || !std::isfinite(d))
                throw SceneError(ParamLoc(m, "density"),
                                 context + ": \"density\" values must be finite and not negative");
        const Vec3f p0 = ps.GetPoint3("p0", Vec3f(0, 0, 0)),
                    p1 = ps.GetPoint3("p1", Vec3f(1, 1, 1));
        if (!(p0.x < p1.x && p0.y < p1.y && p0.z < p1.z))
            throw SceneError(ParamLoc(m, "p1"),
                             context + ": \"p1\" must exceed \"p0\" on every axis");
        const RGB sigmaT = sigmaA + sigmaS;
        if (sigmaT.r != sigmaT.g || sigmaT.r != sigmaT.b)
            ctx.diag.Warn(m.loc, context +
                                     ": a heterogeneous medium's extinction sigma_a + "
                                     "sigma_s is grey; its first (red) channel is used, "
                                     "as in pbrt-v3");
        medium = std::make_unique<GridDensityMedium>(sigmaA, sigmaS, g, step, nx, ny, nz,
                                                     std::move(density), p0, p1,
                                                     ctx.scene.renderFromWorld * m.worldFromMedium);
    } else {
        throw SceneError(m.loc, "unknown medium type " + Quote(m.type) +
                                    " (expected \"homogeneous\" or \"heterogeneous\")");
    }
    ps.ReportUnused(ctx.diag, context);
    return medium;
}

}  // namespace

void BuildMedia(BuildContext &ctx) {
    for (const MediumDesc &m : ctx.desc.media) ctx.scene.media.push_back(MakeMedium(ctx, m));
    const CameraDesc &cam = ctx.desc.camera;
    ctx.scene.cameraMedium = cam.medium;
    if (cam.medium >= 0)
        ctx.scene.features.effects.Enable(Effect::Media,
                                          "camera medium " +
                                              Quote(ctx.desc.media[size_t(cam.medium)].name) +
                                              " (MediumInterface)",
                                          cam.mediumLoc);
}

void WarnIgnoredMedia(BuildContext &ctx) {
    const RenderScene &scene = ctx.scene;
    if (!scene.features.effects.Has(Effect::Media)) return;
    if (scene.integrator->Traits().media) return;
    // pbrt-v3's path and directlighting integrators ignore media too (with a warning).
    ctx.diag.Warn(ctx.desc.integrator.loc,
                  "integrator " + Quote(scene.IntegratorName()) +
                      " ignores participating media (as pbrt-v3's does); \"volpath\" renders "
                      "them");
}

void NoteShapeMedia(BuildContext &ctx, const ShapeDesc &s, ShapeInfo *info) {
    info->mediumInside = s.mediumInside;
    info->mediumOutside = s.mediumOutside;
    if (s.mediumInside == s.mediumOutside) return;  // no transition: nothing changes
    auto name = [&](int i) {
        return i < 0 ? std::string("\"\"") : Quote(ctx.desc.media[size_t(i)].name);
    };
    ctx.scene.features.effects.Enable(
        Effect::Media, "MediumInterface " + name(s.mediumInside) + " " + name(s.mediumOutside),
        s.mediumLoc);
}

}  // namespace prism
