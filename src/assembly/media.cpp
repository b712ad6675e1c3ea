// MakeNamedMedium directives → render/ media (pbrt-v3 api.cpp MakeMedium: names, defaults and
// the "preset" table), and the media effect of shapes and the camera.
#include "assembly/media.h"

#include <algorithm>
#include <cmath>

#include "assembly/scene_effects.h"
#include "render/medium_presets.h"
#include "render/medium_tracked.h"

namespace prism {

namespace {

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
    RGB sigmaA = v4Defaults ? RGB(1) : WholeMilkSigmaA,
        sigmaS = v4Defaults ? RGB(1) : WholeMilkSigmaS;
    const std::string preset = rgbGrid ? "" : ps.GetString("preset", "");
    if (!preset.empty()) {
        if (!MeasuredMedium(preset, &sigmaA, &sigmaS)) {
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
