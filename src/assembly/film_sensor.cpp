#include "assembly/film_sensor.h"

#include <cmath>

#include "assembly/directive_params.h"

namespace prism {

namespace {

using Mat3 = std::array<double, 9>;

Mat3 Mul(const Mat3 &a, const Mat3 &b) {
    Mat3 c{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                c[size_t(3 * i + j)] += a[size_t(3 * i + k)] * b[size_t(3 * k + j)];
    return c;
}

std::array<double, 3> Apply(const Mat3 &m, const std::array<double, 3> &v) {
    return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
            m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

Mat3 Inverse(const Mat3 &m) {
    const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5], g = m[6], h = m[7],
                 i = m[8];
    const double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
    const double det = a * A + b * B + c * C;
    return {A / det, -(b * i - c * h) / det, (b * f - c * e) / det,
            B / det, (a * i - c * g) / det,  -(a * f - c * d) / det,
            C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
}

// sRGB (Rec. 709 primaries, D65) and CIE XYZ; the Bradford cone response.
constexpr Mat3 XYZFromSRGB = {0.4124564, 0.3575761, 0.1804375, 0.2126729, 0.7151522,
                              0.0721750, 0.0193339, 0.1191920, 0.9503041};
constexpr Mat3 Bradford = {0.8951, 0.2664, -0.1614, -0.7502, 1.7135,
                           0.0367, 0.0389, -0.0685, 1.0296};
constexpr std::array<double, 2> D65 = {0.3127, 0.3290};

std::array<double, 3> XYZOfChromaticity(std::array<double, 2> xy) {
    return {xy[0] / xy[1], 1, (1 - xy[0] - xy[1]) / xy[1]};
}

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
    const std::array<double, 3> src = Apply(Bradford, XYZOfChromaticity(from)),
                                dst = Apply(Bradford, XYZOfChromaticity(D65));
    const Mat3 scale = {dst[0] / src[0], 0, 0, 0, dst[1] / src[1], 0, 0, 0, dst[2] / src[2]};
    const Mat3 adapt = Mul(Inverse(Bradford), Mul(scale, Bradford));
    const Mat3 m = Mul(Inverse(XYZFromSRGB), Mul(adapt, XYZFromSRGB));
    std::array<float, 9> out{};
    for (size_t k = 0; k < 9; ++k) out[k] = float(m[k]);
    return out;
}

// Film "rgb", "gbuffer", "spectral" (pbrt-v4's). Parameters:
//   iso           float   100        the sensor's sensitivity: the image x shutter time x
//                                    iso / 100 (pbrt-v4's imaging ratio)
//   whitebalance  float   0          kelvin: daylight of this temperature is rendered white
//                                    (Bradford adaptation to D65); 0: none
//   sensor        string  "cie1931"  the CIE observer; a camera's named sensor is not
//                                    simulated (a warning: cie1931 is used)
//   savefp16      bool    true       read, no effect: Prism's EXR pixels are 32-bit float
void BuildFilmSensor(BuildContext &ctx) {
    const SceneDescription &desc = ctx.desc;
    const std::string &type = desc.film.type;
    if (type != "rgb" && type != "gbuffer" && type != "spectral") return;
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
        scene.filmColor = WhiteBalanceMatrix(DaylightChromaticity(wb));
    }
    WarnIgnored(film, {"savefp16"}, diag, "film", "Prism writes 32-bit float EXR pixels");
    if (type != "rgb")
        diag.Warn(desc.film.loc,
                  "film " + Quote(type) +
                      " is rendered as \"rgb\" (its image, without its own channels)");
}

}  // namespace prism
