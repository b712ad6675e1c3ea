// Tone mapping operators against their published formulas, written out again here
// independently (in double precision, in the form each source publishes), and the exposure.
#include "image/tonemap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace prism {
namespace {

using D3 = std::array<double, 3>;

// Khronos PBR Neutral, as the specification in KhronosGroup/ToneMapping PBR_Neutral/README.md
// states it: F90 = 0.04, Ks = 0.8 - F90, Kd = 0.15;
// f = x - x^2 / (4 F90) for x <= 2 F90, else F90 (x = min(R,G,B));
// p = max(c - f); pn = 1 - (1 - Ks)^2 / (p + 1 - 2 Ks); g = 1 / (Kd (p - pn) + 1);
// out = c - f when p <= Ks, else (c - f) pn / p g + pn (1 - g).
D3 NeutralSpec(D3 c) {
    const double F90 = 0.04, Ks = 0.8 - F90, Kd = 0.15;
    double x = std::min({c[0], c[1], c[2]});
    double f = x <= 2 * F90 ? x - x * x / (4 * F90) : F90;
    double p = std::max({c[0] - f, c[1] - f, c[2] - f});
    D3 out;
    if (p <= Ks) {
        for (int i = 0; i < 3; ++i) out[i] = c[i] - f;
        return out;
    }
    double pn = 1 - (1 - Ks) * (1 - Ks) / (p + 1 - 2 * Ks);
    double g = 1 / (Kd * (p - pn) + 1);
    for (int i = 0; i < 3; ++i) out[i] = (c[i] - f) * pn / p * g + pn * (1 - g);
    return out;
}

// Stephen Hill's ACES fit (BakingLab ACES.hlsl, "ACESFitted"): M_out · RRTAndODTFit(M_in · c),
// saturated. The matrices as published, row by row.
D3 AcesHill(D3 c) {
    const double in[3][3] = {
        {0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}};
    const double out[3][3] = {{1.60475, -0.53108, -0.07367},
                              {-0.10208, 1.10813, -0.00605},
                              {-0.00327, -0.07276, 1.07602}};
    D3 v{}, w{}, r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) v[i] += in[i][j] * c[j];
    for (int i = 0; i < 3; ++i)
        w[i] = (v[i] * (v[i] + 0.0245786) - 0.000090537) /
               (v[i] * (0.983729 * v[i] + 0.4329510) + 0.238081);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) r[i] += out[i][j] * w[j];
        r[i] = std::clamp(r[i], 0.0, 1.0);
    }
    return r;
}

// Hable, "Filmic Tonemapping Operators" (filmicworlds.com, 2010): Uncharted2Tonemap with
// A..F = 0.15, 0.50, 0.10, 0.20, 0.02, 0.30, ExposureBias 2, W = 11.2.
double Uncharted2(double x) {
    const double A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30;
    return ((x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F)) - E / F;
}
D3 HableSpec(D3 c) {
    D3 r;
    for (int i = 0; i < 3; ++i)
        r[i] = std::clamp(Uncharted2(2.0 * c[i]) * (1 / Uncharted2(11.2)), 0.0, 1.0);
    return r;
}

const std::vector<D3> kColors = {
    {0, 0, 0},         {0.01, 0.02, 0.03}, {0.05, 0.1, 0.2}, {0.18, 0.18, 0.18}, {0.5, 0.3, 0.1},
    {0.7, 0.75, 0.74}, {0.8, 0.8, 0.8},    {1, 1, 1},        {1.5, 0.4, 0.2},    {2, 2, 2},
    {4, 1, 0.05},      {10, 10, 10},       {0.2, 3.0, 0.9},  {100, 50, 25},      {1000, 0, 0}};

void ExpectMatches(RGB (*op)(const RGB &), D3 (*spec)(D3), double tol) {
    for (const D3 &c : kColors) {
        RGB got = op(RGB(float(c[0]), float(c[1]), float(c[2])));
        D3 want = spec(c);
        for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(got[i], want[i], tol)
                << "channel " << i << " of (" << c[0] << ", " << c[1] << ", " << c[2] << ")";
    }
}

TEST(ToneMap, NeutralMatchesTheKhronosSpecification) {
    ExpectMatches(ToneMapNeutral, NeutralSpec, 2e-6);
    // Below the compression start the operator is the identity minus the 0.04 offset (for a
    // colour whose smallest channel is past the toe): albedo-like values stay themselves.
    RGB mid = ToneMapNeutral(RGB(0.5f, 0.3f, 0.1f));
    EXPECT_NEAR(mid.r, 0.46, 1e-6);
    EXPECT_NEAR(mid.b, 0.06, 1e-6);
    // Highlights approach white without reaching past it.
    EXPECT_LE(ToneMapNeutral(RGB(1e6f)).r, 1.f);
    EXPECT_GT(ToneMapNeutral(RGB(1e6f)).r, 0.999f);
}

TEST(ToneMap, AcesMatchesHillsFit) {
    ExpectMatches(ToneMapAces, AcesHill, 2e-6);
    EXPECT_NEAR(ToneMapAces(RGB(0.18f)).g, AcesHill({0.18, 0.18, 0.18})[1], 1e-6);
}

TEST(ToneMap, FilmicMatchesHablesCurve) {
    ExpectMatches(ToneMapFilmic, HableSpec, 2e-6);
    // The white point maps to 1 (after the exposure bias of 2: input 5.6).
    EXPECT_NEAR(ToneMapFilmic(RGB(5.6f)).r, 1.0, 1e-6);
}

TEST(ToneMap, NoneClampsAndBadValuesAreSafe) {
    RGB c = ApplyToneMap(ToneMap::None, RGB(-1.f, 0.25f, 7.f));
    EXPECT_EQ(c, RGB(0.f, 0.25f, 1.f));
    for (ToneMap op : {ToneMap::Neutral, ToneMap::Aces, ToneMap::Filmic}) {
        for (float bad : {NAN, INFINITY, -INFINITY, -3.f, 1e30f}) {
            RGB m = ApplyToneMap(op, RGB(bad, 0.5f, 0.5f));
            for (int i = 0; i < 3; ++i) {
                EXPECT_TRUE(m[i] >= 0 && m[i] <= 1) << ToneMapName(op) << " of " << bad;
            }
        }
    }
}

TEST(ToneMap, NamesRoundTrip) {
    for (const char *n : {"none", "neutral", "aces", "filmic"}) {
        ToneMap op;
        ASSERT_TRUE(ParseToneMap(n, &op));
        EXPECT_STREQ(ToneMapName(op), n);
    }
    ToneMap op;
    EXPECT_FALSE(ParseToneMap("reinhard", &op));
}

TEST(OutputTransform, ExposureIsExactAndSparesAlpha) {
    Image img(3, 2, 4);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = 0.1f * float(i) + 0.013f;
    Image twice = img, third = img;
    ApplyOutputTransform(twice, {1.f, ToneMap::None}, true);
    const float s = std::exp2(-1.5f);
    ApplyOutputTransform(third, {-1.5f, ToneMap::Aces}, true);  // linear: no tone map
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        if (i % 4 == 3) {
            EXPECT_EQ(twice.pixels[i], img.pixels[i]);  // alpha
            EXPECT_EQ(third.pixels[i], img.pixels[i]);
        } else {
            EXPECT_EQ(twice.pixels[i], 2 * img.pixels[i]);
            EXPECT_EQ(third.pixels[i], img.pixels[i] * s);
        }
    }
    // Exposure 0, no tone map: untouched.
    Image same = img;
    ApplyOutputTransform(same, {}, false);
    EXPECT_EQ(same.pixels, img.pixels);
}

TEST(OutputTransform, ToneMapsDisplayOutputsAfterExposure) {
    Image img(1, 1, 3);
    img.pixels = {0.6f, 1.2f, 3.f};
    ApplyOutputTransform(img, {1.f, ToneMap::Filmic}, false);
    D3 want = HableSpec({1.2, 2.4, 6.0});
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(img.pixels[size_t(i)], want[size_t(i)], 2e-6);
    Image gray(1, 1, 1);
    gray.pixels = {2.f};
    ApplyOutputTransform(gray, {0.f, ToneMap::Neutral}, false);
    EXPECT_NEAR(gray.pixels[0], NeutralSpec({2, 2, 2})[0], 2e-6);
}

TEST(AutoExposure, MapsTheLogAverageOfLitPixelsToMiddleGrey) {
    Image img(4, 2, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) img.SetRGB(x, y, RGB(0.045f));
    const float ev = float(std::log2(0.18 / (0.045 + 1e-4)));
    EXPECT_NEAR(AutoExposureEV(img), ev, 1e-5);
    // Black pixels (an empty background) and NaN do not count.
    img.SetRGB(0, 0, RGB(0.f));
    img.SetRGB(1, 0, RGB(std::nanf("")));
    EXPECT_NEAR(AutoExposureEV(img), ev, 1e-5);
    // The geometric mean: 0.01 and 1 average as 0.1 (up to the 1e-4 of Reinhard's formula).
    Image two(2, 1, 3);
    two.SetRGB(0, 0, RGB(0.01f));
    two.SetRGB(1, 0, RGB(1.f));
    EXPECT_NEAR(AutoExposureEV(two), std::log2(0.18 / std::sqrt(0.0101 * 1.0001)), 1e-5);
    EXPECT_EQ(AutoExposureEV(Image(3, 3, 3)), 0.f);  // all black
    // Clamped to [-20, 20].
    two.SetRGB(0, 0, RGB(1e-30f));
    two.SetRGB(1, 0, RGB(1e-30f));
    EXPECT_EQ(AutoExposureEV(two), float(std::log2(0.18 / 1e-4)));
    Image bright(1, 1, 3);
    bright.SetRGB(0, 0, RGB(1e12f));
    EXPECT_EQ(AutoExposureEV(bright), -20.f);
}

TEST(AutoExposure, ParseExposure) {
    float ev = 7;
    bool isAuto = true;
    EXPECT_TRUE(ParseExposure("-1.5", &ev, &isAuto));
    EXPECT_EQ(ev, -1.5f);
    EXPECT_FALSE(isAuto);
    EXPECT_TRUE(ParseExposure("auto", &ev, &isAuto));
    EXPECT_TRUE(isAuto);
    for (const char *bad : {"", "65", "-64.5", "1x", "Auto", "nan"})
        EXPECT_FALSE(ParseExposure(bad, &ev, &isAuto)) << bad;
}

}  // namespace
}  // namespace prism
