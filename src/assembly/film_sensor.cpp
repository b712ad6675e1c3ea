#include "assembly/film_sensor.h"

#include <cmath>

#include "assembly/directive_params.h"
#include "core/color_space.h"

namespace prism {

namespace {

// The camera's shutter time (its interval, checked and ordered by BuildCamera).
double ShutterTime(const SceneDescription &desc) {
    const ParamSet &cp = desc.camera.params;
    return std::abs(double(cp.GetFloat("shutterclose", 1)) - cp.GetFloat("shutteropen", 0));
}

}  // namespace

std::array<double, 2> DaylightChromaticity(double T) {
    const double t = T * 1.4388 / 1.4380;
    const double t2 = t * t, t3 = t2 * t;
    const double x = t <= 7000 ? -4.6070e9 / t3 + 2.9678e6 / t2 + 0.09911e3 / t + 0.244063
                               : -2.0064e9 / t3 + 1.9018e6 / t2 + 0.24748e3 / t + 0.237040;
    return {x, -3 * x * x + 2.870 * x - 0.275};
}

std::array<float, 9> WhiteBalanceMatrix(std::array<double, 2> from) {
    return ToFloat(OutputFromSRGB(ColorSpaceId::SRGB, from));
}

// Film "rgb", "gbuffer", "spectral" (pbrt-v4's). Parameters:
//   iso           float   100        the sensor's sensitivity: the image x shutter time x
//                                    iso / 100 (pbrt-v4's imaging ratio)
//   whitebalance  float   0          kelvin: daylight of this temperature is rendered white
//                                    (Bradford adaptation to D65); 0: none
//   sensor        string  "cie1931"  the CIE observer; a camera's named sensor is not
//                                    simulated (a warning: cie1931 is used)
//   savefp16      bool    true       read, no effect: Prism's EXR pixels are 32-bit float
//   coordinatesystem  string  "camera"  gbuffer: the space of P and N; Prism's AOVs are in
//                                    world space (a warning for "camera")
void BuildFilmSensor(BuildContext &ctx) {
    const SceneDescription &desc = ctx.desc;
    const std::string &type = desc.film.type;
    // The film's colour space: the ColorSpace in effect at its Film directive (pbrt-v4's).
    const ColorSpaceId cs = desc.film.colorSpace;
    if (cs != ColorSpaceId::SRGB) {
        const ColorSpaceChromaticities c = Chromaticities(cs);
        ctx.scene.filmChromaticities = {float(c.r[0]), float(c.r[1]), float(c.g[0]), float(c.g[1]),
                                        float(c.b[0]), float(c.b[1]), float(c.w[0]), float(c.w[1])};
    }
    if (type != "rgb" && type != "gbuffer" && type != "spectral") {
        if (cs != ColorSpaceId::SRGB) ctx.scene.filmColor = ToFloat(OutputFromSRGB(cs, {}));
        return;
    }
    const ParamSet &film = desc.film.params;
    Diagnostics &diag = ctx.diag;
    RenderScene &scene = ctx.scene;
    auto locOf = [&](const char *name) {
        const Param *p = film.Find(name);
        return p ? p->loc : desc.film.loc;
    };
    const float iso = film.GetFloat("iso", 100);
    if (!(iso > 0) || !std::isfinite(iso))
        throw SceneError(locOf("iso"), "film \"iso\" must be positive and finite");
    scene.filmScale = float(double(scene.filmScale) * ShutterTime(desc) * iso / 100);
    const std::string sensor = film.GetString("sensor", "cie1931");
    float wb = film.GetFloat("whitebalance", 0);
    if (sensor != "cie1931") {
        diag.Warn(locOf("sensor"), "film sensor " + Quote(sensor) +
                                       " is not simulated: Prism renders the CIE 1931 observer's "
                                       "colours (and balances them to 6500 K, as pbrt-v4 does "
                                       "for a named sensor)");
        if (wb == 0) wb = 6500;
    }
    if (wb != 0) {
        if (!(wb >= 1000 && wb <= 25000))
            throw SceneError(
                locOf("whitebalance"),
                "film \"whitebalance\" must be 0 or a temperature from 1000 to 25000 K");
        if (wb < 3000)
            diag.Warn(locOf("whitebalance"),
                      "film \"whitebalance\" below 3000 K: CIE daylight is defined from 4000 K, "
                      "and pbrt-v4's extrapolated white differs from Prism's there (2000 K: "
                      "red 0.02 where pbrt-v4 has -0.09 on a grey plane)");
    }
    if (wb != 0 || cs != ColorSpaceId::SRGB) {
        std::optional<std::array<double, 2>> balance;
        if (wb != 0) balance = DaylightChromaticity(wb);
        scene.filmColor = ToFloat(OutputFromSRGB(cs, balance));
    }
    WarnIgnored(film, {"savefp16"}, diag, "film", "Prism writes 32-bit float EXR pixels");
    if (type == "gbuffer") {
        // pbrt-v4's geometric channels as Prism's AOVs (render/aov.h), unless the Film names
        // its own (BuildFilm read them): Albedo, P, dzdx/dzdy (depth), N (geometric), Ns
        // (shading), u/v, Variance.
        const bool own = !scene.filmAovs.empty();
        if (!own) scene.filmAovs = "albedo,P,depth,Ng,N,uv,variance";
        const std::string space = film.GetString("coordinatesystem", "camera");
        if (space != "camera" && space != "world")
            throw SceneError(
                locOf("coordinatesystem"),
                "film \"coordinatesystem\" must be \"camera\" or \"world\", not " + Quote(space));
        diag.Warn(
            desc.film.loc,
            "film \"gbuffer\" writes its channels as Prism's AOVs (" +
                (own ? scene.filmAovs : std::string("albedo, P, depth, Ng, N, uv, variance")) +
                ": Prism's channel names, P and N in world space" +
                (space == "camera" ? ", not pbrt-v4's default camera space" : "") + ")");
    } else if (type != "rgb") {
        diag.Warn(desc.film.loc,
                  "film " + Quote(type) +
                      " is rendered as \"rgb\" (its image, without its own channels)");
    }
}

}  // namespace prism
