#include "image/tonemap.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace prism {

namespace {

// Inputs are clamped to [0, 1e18]: the operators' polynomials stay finite (1e36 < FLT_MAX), and
// anything that bright is white under every operator anyway. NaN becomes 0.
float Sanitize(float v) { return v > 0 ? std::min(v, 1e18f) : 0.f; }
RGB Sanitize(const RGB &c) { return {Sanitize(c.r), Sanitize(c.g), Sanitize(c.b)}; }
float Saturate(float v) { return std::clamp(v, 0.f, 1.f); }
RGB Saturate(const RGB &c) { return {Saturate(c.r), Saturate(c.g), Saturate(c.b)}; }

}  // namespace

bool ParseToneMap(const std::string &name, ToneMap *op) {
    for (ToneMap t : {ToneMap::None, ToneMap::Neutral, ToneMap::Aces, ToneMap::Filmic})
        if (name == ToneMapName(t)) {
            *op = t;
            return true;
        }
    return false;
}

const char *ToneMapName(ToneMap op) {
    switch (op) {
        case ToneMap::Neutral:
            return "neutral";
        case ToneMap::Aces:
            return "aces";
        case ToneMap::Filmic:
            return "filmic";
        default:
            return "none";
    }
}

// Khronos PBR Neutral (github.com/KhronosGroup/ToneMapping, PBR_Neutral/README.md): a small
// toe offset f below 2 F90, identity up to Ks = 0.8 - F90, then the peak channel compressed as
// 1 - (1 - Ks)^2 / (p + 1 - 2 Ks) with the colour desaturated toward the new peak.
RGB ToneMapNeutral(const RGB &in) {
    const float startCompression = 0.8f - 0.04f, desaturation = 0.15f;
    RGB c = Sanitize(in);
    float x = std::min({c.r, c.g, c.b});
    float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    c = c - RGB(offset);
    float peak = std::max({c.r, c.g, c.b});
    if (peak < startCompression) return Saturate(c);
    const float d = 1 - startCompression;
    float newPeak = 1 - d * d / (peak + d - startCompression);
    c *= newPeak / peak;
    float g = 1 - 1 / (desaturation * (peak - newPeak) + 1);
    return Saturate(c * (1 - g) + RGB(newPeak) * g);
}

// Stephen Hill's ACES fit (MJP's BakingLab, ACES.hlsl): sRGB → the RRT's saturation-adjusted
// AP1 space, a rational fit of the RRT + ODT tone curve, back to sRGB, clamped.
RGB ToneMapAces(const RGB &in) {
    static constexpr float inputMat[3][3] = {{0.59719f, 0.35458f, 0.04823f},
                                             {0.07600f, 0.90834f, 0.01566f},
                                             {0.02840f, 0.13383f, 0.83777f}};
    static constexpr float outputMat[3][3] = {{1.60475f, -0.53108f, -0.07367f},
                                              {-0.10208f, 1.10813f, -0.00605f},
                                              {-0.00327f, -0.07276f, 1.07602f}};
    auto mul = [](const float m[3][3], const RGB &v) {
        return RGB(m[0][0] * v.r + m[0][1] * v.g + m[0][2] * v.b,
                   m[1][0] * v.r + m[1][1] * v.g + m[1][2] * v.b,
                   m[2][0] * v.r + m[2][1] * v.g + m[2][2] * v.b);
    };
    auto fit = [](float v) {
        float a = v * (v + 0.0245786f) - 0.000090537f;
        float b = v * (0.983729f * v + 0.4329510f) + 0.238081f;
        return a / b;
    };
    RGB v = mul(inputMat, Sanitize(in));
    v = RGB(fit(v.r), fit(v.g), fit(v.b));
    return Saturate(mul(outputMat, v));
}

// John Hable, "Filmic Tonemapping Operators" (2010): the Uncharted 2 curve
// f(x) = (x (A x + C B) + D E) / (x (A x + B) + D F) - E / F with A = 0.15, B = 0.50, C = 0.10,
// D = 0.20, E = 0.02, F = 0.30, applied per channel to 2 x (his exposure bias) and divided by
// f(W) for the white point W = 11.2.
RGB ToneMapFilmic(const RGB &in) {
    auto f = [](float x) {
        const float A = 0.15f, B = 0.50f, C = 0.10f, D = 0.20f, E = 0.02f, F = 0.30f;
        return (x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F) - E / F;
    };
    const float exposureBias = 2.f, white = 11.2f;
    const float whiteScale = 1 / f(white);
    RGB c = Sanitize(in);
    return Saturate(RGB(f(exposureBias * c.r), f(exposureBias * c.g), f(exposureBias * c.b)) *
                    whiteScale);
}

RGB ApplyToneMap(ToneMap op, const RGB &c) {
    switch (op) {
        case ToneMap::Neutral:
            return ToneMapNeutral(c);
        case ToneMap::Aces:
            return ToneMapAces(c);
        case ToneMap::Filmic:
            return ToneMapFilmic(c);
        default:
            return c.Clamped(0.f, 1.f);
    }
}

void ApplyOutputTransform(Image &img, const OutputTransform &t, bool linearOutput) {
    const float scale = std::exp2(t.exposure);
    const bool toneMap = !linearOutput && t.toneMap != ToneMap::None;
    if (scale == 1 && !toneMap) return;
    const int colorChannels = img.channels >= 3 ? 3 : 1;
    const size_t n = size_t(img.width) * size_t(img.height);
    for (size_t i = 0; i < n; ++i) {
        float *p = &img.pixels[i * size_t(img.channels)];
        for (int c = 0; c < colorChannels; ++c) p[c] *= scale;
        if (!toneMap) continue;
        RGB rgb = colorChannels == 3 ? RGB(p[0], p[1], p[2]) : RGB(p[0]);
        RGB m = ApplyToneMap(t.toneMap, rgb);
        if (colorChannels == 3) {
            p[0] = m.r, p[1] = m.g, p[2] = m.b;
        } else {
            p[0] = m.r;
        }
    }
}

float AutoExposureEV(const Image &img) {
    const size_t n = size_t(img.width) * size_t(img.height);
    if (n == 0 || img.channels < 1) return 0;
    double sumLog = 0;
    size_t lit = 0;
    for (size_t i = 0; i < n; ++i) {
        const float *p = &img.pixels[i * size_t(img.channels)];
        const float y = img.channels >= 3 ? RGB(p[0], p[1], p[2]).Luminance() : p[0];
        // Black pixels (an empty background: nothing to expose) and NaN/Inf are left out.
        if (!(y > 0) || !std::isfinite(y)) continue;
        ++lit;
        sumLog += std::log(1e-4 + double(y));
    }
    if (lit == 0) return 0;
    const double logAverage = std::exp(sumLog / double(lit));
    return float(std::clamp(std::log2(0.18 / logAverage), -20.0, 20.0));
}

void ResolveAutoExposure(OutputTransform &t, const Image &img) {
    if (t.autoExposure) t.exposure = AutoExposureEV(img);
}

bool ParseExposure(const std::string &text, float *ev, bool *isAuto) {
    if (text == "auto") {
        *isAuto = true;
        *ev = 0;
        return true;
    }
    char *end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !(v >= -64 && v <= 64)) return false;
    *isAuto = false;
    *ev = float(v);
    return true;
}

}  // namespace prism
