// MakeNamedMedium directives → render/ media (pbrt-v3 api.cpp MakeMedium: names, defaults and
// the "preset" table), and the media effect of shapes and the camera.
#include "assembly/media.h"

#include <algorithm>
#include <cmath>

#include "assembly/scene_effects.h"
#include "render/medium_tracked.h"

namespace prism {

namespace {

// pbrt-v3's GetMediumScatteringProperties table (core/medium.cpp): σ's (reduced scattering,
// used as σs) and σa in mm^-1, from Jensen et al. 2001, "A Practical Model for Subsurface Light
// Transport", and Narasimhan et al. 2006, "Acquiring Scattering Properties of Participating
// Media by Dilution" (every entry of pbrt-v4's table; pbrt-v3's is a subset).
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
    {"Gatorade", {0.0024574f, 0.003007f, 0.0037325f}, {0.024794f, 0.019289f, 0.008878f}},
    {"Chardonnay", {1.7982e-05f, 1.3758e-05f, 1.2023e-05f}, {0.010782f, 0.011855f, 0.023997f}},
    {"White Zinfandel", {1.7501e-05f, 1.9069e-05f, 1.288e-05f}, {0.012072f, 0.016184f, 0.019843f}},
    {"Merlot", {2.1129e-05f, 0.f, 0.f}, {0.11632f, 0.25191f, 0.29434f}},
    {"Budweiser Beer", {2.4356e-05f, 2.4079e-05f, 1.0564e-05f}, {0.011492f, 0.024911f, 0.057786f}},
    {"Coors Light Beer", {5.0922e-05f, 4.301e-05f, 0.f}, {0.006164f, 0.013984f, 0.034983f}},
    {"Clorox", {0.0024035f, 0.0031373f, 0.003991f}, {0.0033542f, 0.014892f, 0.026297f}},
    {"Apple Juice", {0.00013612f, 0.00015836f, 0.000227f}, {0.012957f, 0.023741f, 0.052184f}},
    {"Cranberry Juice", {0.00010402f, 0.00011646f, 7.8139e-05f}, {0.039437f, 0.094223f, 0.12426f}},
    {"Grape Juice", {5.382e-05f, 0.f, 0.f}, {0.10404f, 0.23958f, 0.29325f}},
    {"Ruby Grapefruit Juice", {0.011002f, 0.010927f, 0.011036f}, {0.085867f, 0.18314f, 0.25262f}},
    {"White Grapefruit Juice", {0.22826f, 0.23998f, 0.32748f}, {0.0138f, 0.018831f, 0.056781f}},
    {"Shampoo", {0.0007176f, 0.0008303f, 0.0009016f}, {0.014107f, 0.045693f, 0.061717f}},
    {"Strawberry Shampoo", {0.00015671f, 0.00015947f, 1.518e-05f}, {0.01449f, 0.05796f, 0.075823f}},
    {"Head & Shoulders Shampoo",
     {0.023805f, 0.028804f, 0.034306f},
     {0.084621f, 0.15688f, 0.20365f}},
    {"Lemon Tea Powder", {0.040224f, 0.045264f, 0.051081f}, {2.4288f, 4.5757f, 7.2127f}},
    {"Orange Powder", {0.00015617f, 0.00017482f, 0.0001762f}, {0.001449f, 0.003441f, 0.007863f}},
    {"Pink Lemonade Powder",
     {0.00012103f, 0.00013073f, 0.00012528f},
     {0.001165f, 0.002366f, 0.003195f}},
    {"Cappuccino Powder", {1.8436f, 2.5851f, 2.1662f}, {35.844f, 49.547f, 61.084f}},
    {"Salt Powder", {0.027333f, 0.032451f, 0.031979f}, {0.28415f, 0.3257f, 0.34148f}},
    {"Sugar Powder", {0.00022272f, 0.00025513f, 0.000271f}, {0.012638f, 0.031051f, 0.050124f}},
    {"Suisse Mocha Powder", {2.7979f, 3.5452f, 4.3365f}, {17.502f, 27.004f, 35.433f}},
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

struct GridSize {
    int nx = 1, ny = 1, nz = 1;
    uint64_t Count() const { return uint64_t(nx) * uint64_t(ny) * uint64_t(nz); }
};

GridSize ReadGridSize(const MediumDesc &m, const std::string &context) {
    const ParamSet &ps = m.params;
    const GridSize size{ps.GetInt("nx", 1), ps.GetInt("ny", 1), ps.GetInt("nz", 1)};
    for (const char *n : {"nx", "ny", "nz"})
        if (ps.GetInt(n, 1) < 1 || ps.GetInt(n, 1) > 4096)
            throw SceneError(ParamLoc(m, n),
                             context + ": \"" + n + "\" must be 1 to 4096 grid samples");
    return size;
}

// "p0" and "p1": the box of the medium's space a grid or cloud fills.
void ReadBox(const MediumDesc &m, const std::string &context, Vec3f *p0, Vec3f *p1) {
    *p0 = m.params.GetPoint3("p0", Vec3f(0, 0, 0));
    *p1 = m.params.GetPoint3("p1", Vec3f(1, 1, 1));
    bool finite = true;
    for (int i = 0; i < 3; ++i) finite &= std::isfinite((*p0)[i]) && std::isfinite((*p1)[i]);
    if (!(p0->x < p1->x && p0->y < p1->y && p0->z < p1->z) || !finite)
        throw SceneError(ParamLoc(m, "p1"), context + ": \"p1\" must exceed \"p0\" on every axis");
}

// An "rgbgrid" coefficient: nx*ny*nz RGB values, or none (1 everywhere).
std::vector<RGB> ReadRGBGrid(const MediumDesc &m, const std::string &context, const char *name,
                             const GridSize &size) {
    std::vector<RGB> values = m.params.GetRGBs(name);
    if (!values.empty() && values.size() != size.Count())
        throw SceneError(ParamLoc(m, name),
                         context + ": \"" + name + "\" has " + std::to_string(values.size()) +
                             " RGB values but nx*ny*nz is " + std::to_string(size.Count()));
    for (const RGB &v : values)
        if (v.r < 0 || v.g < 0 || v.b < 0 || !v.IsFinite())
            throw SceneError(ParamLoc(m, name),
                             context + ": \"" + name + "\" values must be finite and not negative");
    return values;
}

// MakeNamedMedium "homogeneous", "heterogeneous", "uniformgrid", "rgbgrid", "cloud" (pbrt-v3's
// two, pbrt-v4's density grid read as "heterogeneous", and pbrt-v4's RGB grid and cloud).
// Parameters:
//   preset             string    ""     a measured medium of pbrt's table (its sigma_a and
//                                       sigma_s; unknown: the defaults, with a warning); not
//                                       for "rgbgrid"
//   sigma_a, sigma_s   spectrum  .0011 .0024 .014, 2.55 3.21 3.77  absorption and
//                                       scattering, per unit length (pbrt-v3's whole milk;
//                                       1 1 1 each for pbrt-v4's types and for a file read by
//                                       pbrt-v4's rules, as pbrt-v4); "rgbgrid": nx ny nz RGB
//                                       values each, x fastest, or absent (1 everywhere)
//   scale              float     1      multiplies both, >= 0
//   g                  float     0      Henyey-Greenstein asymmetry, in (-1, 1)
//   stepsize           float     0      the single-scattering ray march's step (a Prism
//                                       extension; 0: an eighth of the mean free path)
//   nx, ny, nz         integer   1      grids: the grid's size, 1 to 4096
//   density            float[]   —      "heterogeneous", "uniformgrid": nx ny nz values, x
//                                       fastest; required. "cloud": one value, default 1, how
//                                       dense the cloud is
//   wispiness          float     1      "cloud": how far noise bends the cloud into wisps
//   frequency          float     5      "cloud": the noise's frequency in the medium's space
//   p0, p1             point     0 0 0, 1 1 1  grids and cloud: the box filled
//   Le                 spectrum  0      pbrt-v4's emission ("rgbgrid": nx ny nz values): read,
//                                       not simulated (a warning when it would emit)
//   Lescale            float     1      pbrt-v4's: read, not simulated
//   temperature        float[]   —      pbrt-v4's: read, not simulated (a warning)
//   temperaturescale   float     1      pbrt-v4's: read, not simulated
//   temperatureoffset  float     0      pbrt-v4's: read, not simulated
//   temperaturecutoff  float     0      pbrt-v4's: read, not simulated
std::unique_ptr<Medium> MakeMedium(BuildContext &ctx, const MediumDesc &m) {
    const ParamSet &ps = m.params;
    const std::string context = "medium " + Quote(m.name);
    const bool grid = m.type == "heterogeneous" || m.type == "uniformgrid";
    const bool rgbGrid = m.type == "rgbgrid", cloud = m.type == "cloud";
    if (!(m.type == "homogeneous" || grid || rgbGrid || cloud))
        throw SceneError(m.loc, "unknown medium type " + Quote(m.type) +
                                    " (expected \"homogeneous\", \"heterogeneous\", "
                                    "\"uniformgrid\", \"rgbgrid\" or \"cloud\"; pbrt-v4's "
                                    "\"nanovdb\" is not supported: Debian 12 has no NanoVDB)");
    const bool v4Defaults = m.type == "uniformgrid" || rgbGrid || cloud ||
                            (m.type == "homogeneous" && ctx.desc.pbrtVersion.version == 4);
    RGB sigmaA = v4Defaults ? RGB(1) : DefaultSigmaA, sigmaS = v4Defaults ? RGB(1) : DefaultSigmaS;
    const std::string preset = rgbGrid ? "" : ps.GetString("preset", "");
    if (!preset.empty()) {
        const MediumPreset *found = nullptr;
        for (const MediumPreset &p : Presets)
            if (preset == p.name) found = &p;
        if (found) {
            sigmaA = found->sigmaA;
            sigmaS = found->sigmaPrimeS;
        } else {
            ctx.diag.Warn(ParamLoc(m, "preset"),
                          context + ": unknown preset " + Quote(preset) + "; using the default (" +
                              (v4Defaults ? "pbrt-v4's, 1 1 1" : "pbrt-v3's, whole milk") + ")");
        }
    }
    const float scale = ps.GetFloat("scale", 1.f);
    const float g = ps.GetFloat("g", 0.f);
    if (!rgbGrid) {
        sigmaA = ps.GetRGB("sigma_a", sigmaA);
        sigmaS = ps.GetRGB("sigma_s", sigmaS);
        CheckNonNegative(m, "sigma_a", sigmaA);
        CheckNonNegative(m, "sigma_s", sigmaS);
    }
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
    // pbrt-v4's emissive media: read, not simulated.
    bool emits = !ps.GetFloats("temperature").empty();
    for (const RGB &le : ps.Has("Le") ? ps.GetRGBs("Le") : std::vector<RGB>())
        emits |= !le.IsBlack();
    WarnIgnored(ps,
                {"Le", "Lescale", "temperature", "temperaturescale", "temperatureoffset",
                 "temperaturecutoff"},
                ctx.diag, context,
                emits ? "Prism's media do not emit; the medium absorbs and scatters only" : "");
    const Transform renderFromMedium = ctx.scene.renderFromWorld * m.worldFromMedium;
    std::unique_ptr<Medium> medium;
    if (m.type == "homogeneous") {
        medium = std::make_unique<HomogeneousMedium>(sigmaA, sigmaS, g, step);
    } else if (grid) {
        const GridSize size = ReadGridSize(m, context);
        if (!ps.Has("density"))
            throw SceneError(m.loc, context + ": a grid medium needs \"density\" values");
        std::vector<float> density = ps.GetFloats("density");
        if (density.size() != size.Count())
            throw SceneError(ParamLoc(m, "density"),
                             context + ": \"density\" has " + std::to_string(density.size()) +
                                 " values but nx*ny*nz is " + std::to_string(size.Count()));
        for (float d : density)
            if (!(d >= 0) || !std::isfinite(d))
                throw SceneError(ParamLoc(m, "density"),
                                 context + ": \"density\" values must be finite and not negative");
        Vec3f p0, p1;
        ReadBox(m, context, &p0, &p1);
        if (m.type == "uniformgrid") {
            // pbrt-v4's grid: chromatic extinction, tracked per channel.
            medium = std::make_unique<DensityGridMedium>(sigmaA, sigmaS, g, step, size.nx, size.ny,
                                                         size.nz, std::move(density), p0, p1,
                                                         renderFromMedium);
        } else {
            const RGB sigmaT = sigmaA + sigmaS;
            if (sigmaT.r != sigmaT.g || sigmaT.r != sigmaT.b)
                ctx.diag.Warn(m.loc, context +
                                         ": a grid medium's extinction sigma_a + sigma_s "
                                         "is grey; its first (red) channel is used, as in "
                                         "pbrt-v3");
            medium = std::make_unique<GridDensityMedium>(sigmaA, sigmaS, g, step, size.nx, size.ny,
                                                         size.nz, std::move(density), p0, p1,
                                                         renderFromMedium);
        }
    } else if (rgbGrid) {
        const GridSize size = ReadGridSize(m, context);
        std::vector<RGB> a = ReadRGBGrid(m, context, "sigma_a", size),
                         s = ReadRGBGrid(m, context, "sigma_s", size);
        if (a.empty() && s.empty())
            throw SceneError(m.loc, context +
                                        ": an \"rgbgrid\" medium needs \"sigma_a\" or "
                                        "\"sigma_s\" values");
        Vec3f p0, p1;
        ReadBox(m, context, &p0, &p1);
        medium = std::make_unique<RGBGridMedium>(g, step, size.nx, size.ny, size.nz, std::move(a),
                                                 std::move(s), scale, p0, p1, renderFromMedium);
    } else {
        const float density = ps.GetFloat("density", 1.f), wisp = ps.GetFloat("wispiness", 1.f),
                    frequency = ps.GetFloat("frequency", 5.f);
        for (const char *n : {"density", "wispiness", "frequency"})
            if (!(ps.GetFloat(n, 1.f) >= 0) || !std::isfinite(ps.GetFloat(n, 1.f)))
                throw SceneError(ParamLoc(m, n),
                                 context + ": \"" + n + "\" must be finite and not negative");
        Vec3f p0, p1;
        ReadBox(m, context, &p0, &p1);
        medium = std::make_unique<CloudMedium>(sigmaA, sigmaS, g, step, density, wisp, frequency,
                                               p0, p1, renderFromMedium);
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
