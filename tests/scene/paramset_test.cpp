#include "scene/paramset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "scene/pbrt_parser.h"
#include "scene/spectrum.h"
#include "support/errors.h"

namespace prism {
namespace {

using namespace test;

// Parses `Shape "test" <params>` and returns the shape's parameter list.
ParamSet Params(const std::string &params, const std::string &file = "p.pbrt") {
    Diagnostics diag;
    SceneDescription s = ParsePbrtString("WorldBegin Shape \"test\" " + params, file, diag);
    EXPECT_EQ(s.shapes.size(), 1u);
    return s.shapes.empty() ? ParamSet() : s.shapes[0].params;
}

std::string ParamError(const std::string &params) {
    return PbrtErrorOf("WorldBegin Shape \"test\" " + params, {}, "p.pbrt");
}

template <typename F>
std::string LookupError(F f) {
    return ErrorOf<SceneError>(f);
}

void ExpectRGBNear(const RGB &a, const RGB &b, float tol) {
    EXPECT_NEAR(a.r, b.r, tol);
    EXPECT_NEAR(a.g, b.g, tol);
    EXPECT_NEAR(a.b, b.b, tol);
}

TEST(ParamSet, ScalarTypes) {
    ParamSet ps = Params(R"("float radius" 2.5 "integer n" [3] "bool on" "true"
                            "bool off" false "string name" ["abc"] "texture Kd" "tex")");
    EXPECT_FLOAT_EQ(ps.GetFloat("radius", 1), 2.5f);
    EXPECT_EQ(ps.GetInt("n", 0), 3);
    EXPECT_TRUE(ps.GetBool("on", false));
    EXPECT_FALSE(ps.GetBool("off", true));
    EXPECT_EQ(ps.GetString("name", ""), "abc");
    EXPECT_EQ(ps.GetTexture("Kd"), "tex");
}

TEST(ParamSet, DefaultsWhenAbsent) {
    ParamSet ps = Params("");
    EXPECT_FLOAT_EQ(ps.GetFloat("radius", 1.5f), 1.5f);
    EXPECT_EQ(ps.GetInt("n", 7), 7);
    EXPECT_TRUE(ps.GetBool("b", true));
    EXPECT_EQ(ps.GetString("s", "dflt"), "dflt");
    EXPECT_EQ(ps.GetPoint3("p", Vec3f(1, 2, 3)), Vec3f(1, 2, 3));
    EXPECT_EQ(ps.GetVector3("v", Vec3f(0, 0, 1)), Vec3f(0, 0, 1));
    EXPECT_EQ(ps.GetNormal("n3", Vec3f(0, 1, 0)), Vec3f(0, 1, 0));
    EXPECT_EQ(ps.GetRGB("Kd", RGB(0.5f)), RGB(0.5f));
    EXPECT_EQ(ps.GetTexture("Kd"), "");
    EXPECT_TRUE(ps.GetFloats("f").empty());
    EXPECT_TRUE(ps.GetInts("i").empty());
    EXPECT_TRUE(ps.GetPoint2s("uv").empty());
    EXPECT_TRUE(ps.GetPoint3s("P").empty());
    EXPECT_TRUE(ps.GetNormals("N").empty());
    EXPECT_TRUE(ps.GetStrings("s").empty());
}

TEST(ParamSet, GeometricTypesAndSpellings) {
    ParamSet ps = Params(R"("point from" [1 2 3] "point3 to" [4 5 6] "vector up" [0 1 0]
        "vector3 dir" [0 0 -1] "normal N" [0 0 1 0 1 0] "normal3 n3" [1 0 0]
        "point2 uv" [0 0 1 0 1 1] "vector2 d2" [1 2] "float st" [0.5 0.25 1 1]
        "point P" [0 0 0 1 0 0 0 1 0])");
    EXPECT_EQ(ps.GetPoint3("from", {}), Vec3f(1, 2, 3));
    EXPECT_EQ(ps.GetPoint3("to", {}), Vec3f(4, 5, 6));
    EXPECT_EQ(ps.GetVector3("up", {}), Vec3f(0, 1, 0));
    EXPECT_EQ(ps.GetVector3("dir", {}), Vec3f(0, 0, -1));
    EXPECT_EQ(ps.GetNormal("n3", {}), Vec3f(1, 0, 0));
    auto normals = ps.GetNormals("N");
    ASSERT_EQ(normals.size(), 2u);
    EXPECT_EQ(normals[1], Vec3f(0, 1, 0));
    auto uv = ps.GetPoint2s("uv");
    ASSERT_EQ(uv.size(), 3u);
    EXPECT_EQ(uv[2], Vec2f(1, 1));
    auto st = ps.GetPoint2s("st");  // pbrt-v3 "float st" flat arrays
    ASSERT_EQ(st.size(), 2u);
    EXPECT_EQ(st[0], Vec2f(0.5f, 0.25f));
    auto P = ps.GetPoint3s("P");
    ASSERT_EQ(P.size(), 3u);
    EXPECT_EQ(P[1], Vec3f(1, 0, 0));
    EXPECT_EQ(ps.Find("d2")->type, ParamType::Vector2);
    EXPECT_EQ(ps.Find("from")->spelledType, "point");
}

TEST(ParamSet, ArraysAndFirstValueOfArrays) {
    ParamSet ps = Params(R"("integer indices" [0 1 2 2 3 0] "float f" [1 2 3]
                            "string names" ["a" "b"])");
    auto idx = ps.GetInts("indices");
    EXPECT_EQ(idx, (std::vector<int>{0, 1, 2, 2, 3, 0}));
    EXPECT_EQ(ps.GetInt("indices", -1), 0);  // single-value lookups take the first value
    EXPECT_FLOAT_EQ(ps.GetFloat("f", 0), 1.f);
    EXPECT_EQ(ps.GetFloats("f"), (std::vector<float>{1, 2, 3}));
    EXPECT_EQ(ps.GetFloats("indices").size(), 6u);  // integers are acceptable as floats
    EXPECT_EQ(ps.GetStrings("names"), (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(ps.GetString("names", ""), "a");
}

TEST(ParamSet, LaterParameterOfSameNameWins) {
    ParamSet ps = Params(R"("float radius" 1 "float radius" 3)");
    EXPECT_EQ(ps.Params().size(), 1u);
    EXPECT_FLOAT_EQ(ps.GetFloat("radius", 0), 3.f);
}

TEST(ParamSet, WrongTypeLookupErrors) {
    ParamSet ps = Params(R"("string radius" "big" "color Kd" [1 0 0] "float n" 2)");
    EXPECT_EQ(LookupError([&] { ps.GetFloat("radius", 1); }),
              "p.pbrt:1:25: error: parameter \"radius\" must be float, not string");
    EXPECT_EQ(LookupError([&] { ps.GetTexture("Kd"); }), "no error");
    EXPECT_EQ(ps.GetTexture("Kd"), "");
    EXPECT_EQ(LookupError([&] { ps.GetFloat("Kd", 1); }),
              "p.pbrt:1:47: error: parameter \"Kd\" must be float, not color");
    EXPECT_EQ(LookupError([&] { ps.GetInt("n", 1); }),
              "p.pbrt:1:66: error: parameter \"n\" must be integer, not float");
    EXPECT_EQ(LookupError([&] { ps.GetPoint3s("n"); }),
              "p.pbrt:1:66: error: parameter \"n\" must be point3, not float");
    EXPECT_EQ(LookupError([&] { ps.GetBool("n", false); }),
              "p.pbrt:1:66: error: parameter \"n\" must be bool, not float");
    EXPECT_EQ(LookupError([&] { ps.GetRGB("radius", {}); }),
              "p.pbrt:1:25: error: parameter \"radius\" must be rgb, not string");
}

TEST(ParamSet, PointVectorNormalAreDistinct) {
    ParamSet ps = Params(R"("point p" [1 2 3] "vector v" [1 2 3] "normal n" [0 0 1])");
    EXPECT_NE(LookupError([&] { ps.GetVector3("p", {}); }), "no error");
    EXPECT_NE(LookupError([&] { ps.GetPoint3("v", {}); }), "no error");
    EXPECT_NE(LookupError([&] { ps.GetPoint3("n", {}); }), "no error");
    EXPECT_NE(LookupError([&] { ps.GetNormal("p", {}); }), "no error");
}

TEST(ParamSet, OddFloatArrayAsPoint2IsAnError) {
    ParamSet ps = Params(R"("float uv" [0 1 2])");
    EXPECT_NE(LookupError([&] { ps.GetPoint2s("uv"); }).find("even number"), std::string::npos);
}

TEST(ParamSet, ReportUnused) {
    ParamSet ps = Params(R"("float radius" 1 "float foo" 2 "float bar" 3)");
    ps.GetFloat("radius", 0);
    ps.MarkUsed("bar");
    Diagnostics diag;
    ps.ReportUnused(diag, "shape \"sphere\"");
    auto w = diag.Warnings();
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].ToString(), "p.pbrt:1:42: warning: unused parameter \"foo\" (shape \"sphere\")");
    Diagnostics diag2;
    ps.ReportUnused(diag2, "");
    ASSERT_EQ(diag2.Warnings().size(), 1u);
    EXPECT_EQ(diag2.Warnings()[0].message, "unused parameter \"foo\"");
}

TEST(ParamSet, AddReplacesAndFind) {
    ParamSet ps;
    Param p;
    p.type = ParamType::Integer;
    p.name = "n";
    p.numbers = {4};
    ps.Add(p);
    p.numbers = {5};
    ps.Add(p);
    EXPECT_EQ(ps.Params().size(), 1u);
    EXPECT_TRUE(ps.Has("n"));
    EXPECT_FALSE(ps.Has("m"));
    EXPECT_EQ(ps.GetInt("n", 0), 5);
    EXPECT_STREQ(ParamTypeName(ParamType::Normal), "normal");
}

TEST(ParamSet, RGBAndXYZ) {
    ParamSet ps = Params(R"("rgb a" [0.1 0.2 0.3] "color b" [1 1 1] "xyz c" [0.95047 1 1.08883])");
    EXPECT_EQ(ps.GetRGB("a", {}), RGB(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(ps.GetRGB("b", {}), RGB(1.f));
    // D65 white (published XYZ, Y = 1) → sRGB white, to float rounding of the matrix.
    ExpectRGBNear(ps.GetRGB("c", {}), RGB(1.f), 1e-6f);
}

TEST(ParamSet, BlackbodyConversion) {
    ParamSet ps = Params(R"("blackbody L" [6500 2] "blackbody warm" [2000 1]
                            "blackbody v4" [6500] "blackbody two" [6500 1 2000 3])");
    RGB l = ps.GetRGB("L", {});
    RGB ref = BlackbodyToRGB(6500, 1);
    ExpectRGBNear(l, ref * 2.f, 1e-5f);
    ExpectRGBNear(ps.GetRGB("v4", {}), ref, 1e-5f);
    // 6500 K is close to the sRGB white point: nearly grey after normalization.
    EXPECT_NEAR(ref.r / ref.g, 1.0, 0.08);
    EXPECT_NEAR(ref.b / ref.g, 1.0, 0.08);
    RGB warm = ps.GetRGB("warm", {});
    EXPECT_GT(warm.r, warm.g);
    EXPECT_GT(warm.g, warm.b);
    const Param *two = ps.Find("two");
    ASSERT_EQ(two->numbers.size(), 6u);
    EXPECT_NEAR(two->numbers[3], 3 * warm.r, 1e-5);
}

// Independent closed forms for the spectral tests: Wyman, Sloan and Shirley 2013, multi-lobe
// fit (their equation 2 and table 1), Planck's law, and the sRGB matrices.
double Piecewise(double l, double mu, double s1, double s2) {
    double t = (l - mu) * (l < mu ? s1 : s2);
    return std::exp(-0.5 * t * t);
}
double WymanX(double l) {
    return 1.056 * Piecewise(l, 599.8, 0.0264, 0.0323) +
           0.362 * Piecewise(l, 442.0, 0.0624, 0.0374) -
           0.065 * Piecewise(l, 501.1, 0.0490, 0.0382);
}
double WymanY(double l) {
    return 0.821 * Piecewise(l, 568.8, 0.0213, 0.0247) +
           0.286 * Piecewise(l, 530.9, 0.0613, 0.0322);
}
double WymanZ(double l) {
    return 1.217 * Piecewise(l, 437.0, 0.0845, 0.0278) +
           0.681 * Piecewise(l, 459.0, 0.0385, 0.0725);
}
double PlanckLaw(double nm, double T) {
    const double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23, l = nm * 1e-9;
    return 2 * h * c * c / (std::pow(l, 5) * std::expm1(h * c / (l * kb * T)));
}
// CIE 1931 xy chromaticity of a linear sRGB colour (the inverse of XYZToRGB's matrix).
std::pair<double, double> Chromaticity(const RGB &c) {
    double r = c.r, g = c.g, b = c.b;
    double X = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    double Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    double Z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
    return {X / (X + Y + Z), Y / (X + Y + Z)};
}

TEST(Spectrum, ColorMatchingFunctionsAreTheWymanFit) {
    for (double l = 360; l <= 830; l += 0.5) {
        EXPECT_NEAR(CIEXBar(l), WymanX(l), 1e-12) << l;
        EXPECT_NEAR(CIEYBar(l), WymanY(l), 1e-12) << l;
        EXPECT_NEAR(CIEZBar(l), WymanZ(l), 1e-12) << l;
    }
    // Against the tabulated CIE 1931 2° functions: the fit is within 0.011 of every entry here
    // (its largest error is about 1% of the peak).
    struct Row {
        double l, x, y, z;
    };
    const Row table[] = {{400, 0.01431, 0.000396, 0.06785}, {445, 0.3481, 0.0298, 1.7826},
                         {450, 0.3362, 0.0380, 1.77211},    {500, 0.0049, 0.3230, 0.2720},
                         {550, 0.43345, 0.99495, 0.00875},  {555, 0.5121, 1.0000, 0.00575},
                         {600, 1.0622, 0.6310, 0.0008},     {650, 0.2835, 0.1070, 0.0},
                         {700, 0.011359, 0.004102, 0.0}};
    for (const Row &r : table) {
        EXPECT_NEAR(CIEXBar(r.l), r.x, 0.011) << r.l;
        EXPECT_NEAR(CIEYBar(r.l), r.y, 0.011) << r.l;
        EXPECT_NEAR(CIEZBar(r.l), r.z, 0.011) << r.l;
    }
}

TEST(Spectrum, BlackbodyIsThePlanckIntegral) {
    // XYZ = sum over 1 nm of Planck x CMF / sum of ybar (pbrt-v3's normalization), computed here
    // independently; the peak normalization (Wien) drops out of the chromaticity, so compare
    // the RGB's ratios and its chromaticity.
    for (double T : {2000.0, 2856.0, 4000.0, 6500.0, 10000.0}) {
        double X = 0, Y = 0, Z = 0;
        for (int l = 360; l <= 830; ++l) {
            double p = PlanckLaw(l, T);
            X += p * WymanX(l);
            Y += p * WymanY(l);
            Z += p * WymanZ(l);
        }
        RGB want = XYZToRGB(X, Y, Z), got = BlackbodyToRGB(T);
        EXPECT_NEAR(got.r / got.g, want.r / want.g, 2e-6 * want.r / want.g) << T;
        EXPECT_NEAR(got.b / got.g, want.b / want.g, 2e-6 * want.b / want.g) << T;
    }
    // The Planckian locus (published CIE 1931 xy): the Wyman fit moves it by at most 0.0027.
    struct Locus {
        double T, x, y, tol;
    };
    const Locus locus[] = {{2000, 0.5267, 0.4133, 0.003},
                           {2856, 0.44757, 0.40745, 0.0015},  // CIE illuminant A
                           {6500, 0.3135, 0.3237, 0.0003},
                           {10000, 0.2807, 0.2884, 0.0003}};
    for (const Locus &c : locus) {
        auto [x, y] = Chromaticity(BlackbodyToRGB(c.T));
        EXPECT_NEAR(x, c.x, c.tol) << c.T;
        EXPECT_NEAR(y, c.y, c.tol) << c.T;
    }
}

TEST(Spectrum, ColorMatchingFunctionFit) {
    // Peaks of the CIE 1931 functions: x̄(600)≈1.06, ȳ(555)≈1.00, z̄(445)≈1.78.
    EXPECT_NEAR(CIEXBar(600), 1.062, 0.02);
    EXPECT_NEAR(CIEYBar(555), 1.000, 0.02);
    EXPECT_NEAR(CIEZBar(445), 1.78, 0.04);
    EXPECT_NEAR(CIEYBar(400), 0.0004, 0.005);
}

TEST(Spectrum, FlatSpectrumIsEqualEnergyWhite) {
    // pbrt's FromSampled convention: a flat spectrum of 1 has XYZ ≈ (1,1,1), which is the
    // equal-energy white E, slightly reddish in (D65-white) sRGB.
    RGB flat = SampledToRGB({{300, 1}, {900, 1}});
    RGB e = XYZToRGB(1, 1, 1);
    ExpectRGBNear(flat, e, 0.03f * 1.2f);
    EXPECT_NEAR(flat.Luminance(), 1.0, 0.01);
    // Exactly: XYZ = (sum xbar, sum ybar, sum zbar) / sum ybar over the 1 nm grid, which the
    // Wyman fit puts within 0.25% of E's (1, 1, 1).
    double sx = 0, sy = 0, sz = 0;
    for (int l = 360; l <= 830; ++l) {
        sx += WymanX(l);
        sy += WymanY(l);
        sz += WymanZ(l);
    }
    ExpectRGBNear(flat, XYZToRGB(sx / sy, 1, sz / sy), 2e-6f);
    EXPECT_NEAR(sx / sy, 1, 0.0025);
    EXPECT_NEAR(sz / sy, 1, 0.0025);
    // Linear in the spectrum's scale, and clamped outside the sampled range.
    ExpectRGBNear(SampledToRGB({{500, 0.25}}), flat * 0.25f, 1e-5f);
    EXPECT_EQ(SampledToRGB({}), RGB(0.f));
}

TEST(Spectrum, PiecewiseLinearAndSorted) {
    RGB a = SampledToRGB({{400, 0}, {700, 1}});
    RGB b = SampledToRGB({{700, 1}, {400, 0}});
    EXPECT_EQ(a, b);
    EXPECT_GT(a.r, a.b);  // a ramp rising toward red
}

TEST(Spectrum, Blackbody) {
    RGB hot = BlackbodyToRGB(10000), cool = BlackbodyToRGB(2000);
    EXPECT_GT(hot.b, hot.r);
    EXPECT_GT(cool.r, cool.g);
    EXPECT_GT(cool.g, cool.b);
    EXPECT_EQ(BlackbodyToRGB(0), RGB(0.f));
    EXPECT_EQ(BlackbodyToRGB(-5), RGB(0.f));
    ExpectRGBNear(BlackbodyToRGB(5000, 3), BlackbodyToRGB(5000) * 3.f, 1e-5f);
}

TEST(ParamSet, InlineSpectrum) {
    ParamSet ps = Params(R"("spectrum Kd" [300 0.5 800 0.5])");
    ExpectRGBNear(ps.GetRGB("Kd", {}), SampledToRGB({{400, 0.5}}), 1e-5f);
    EXPECT_NE(ParamError(R"("spectrum Kd" [300 0.5 800])").find("multiple of 2"),
              std::string::npos);
}

TEST(ParamSet, SpectrumFiles) {
    namespace fs = std::filesystem;
    fs::path dir = fs::path(::testing::TempDir()) / "prism_spd_test";
    fs::create_directories(dir / "spds");
    std::ofstream(dir / "spds" / "flat.spd") << "# comment\n300 2.0\n# more\n900 2.0\n";
    std::ofstream(dir / "spds" / "bad.spd") << "300 abc\n";
    std::string scene = (dir / "scene.pbrt").string();
    Diagnostics diag;
    SceneDescription s = ParsePbrtString(
        R"(WorldBegin Shape "test" "spectrum eta" "spds/flat.spd" "spectrum k" "missing.spd"
           "spectrum bad" "spds/bad.spd")",
        scene, diag);
    const ParamSet &ps = s.shapes[0].params;
    ExpectRGBNear(ps.GetRGB("eta", {}), SampledToRGB({{500, 2.0}}), 1e-5f);
    EXPECT_EQ(ps.GetRGB("k", {}), RGB(1.f));    // missing file → grey 1 with a warning
    EXPECT_EQ(ps.GetRGB("bad", {}), RGB(1.f));  // unreadable → grey 1 with a warning
    auto w = diag.Warnings();
    ASSERT_EQ(w.size(), 2u);
    EXPECT_NE(w[0].message.find("cannot open spectrum file \"missing.spd\""), std::string::npos);
    EXPECT_NE(w[1].message.find("cannot read spectrum file \"spds/bad.spd\""), std::string::npos);
}

TEST(ParamSet, ValueKindErrors) {
    EXPECT_EQ(ParamError(R"("float radius" "big")"),
              "p.pbrt:1:25: error: parameter \"radius\": expected numbers, got strings");
    EXPECT_EQ(ParamError(R"("string s" [1])"),
              "p.pbrt:1:25: error: parameter \"s\": expected strings, got numbers");
    EXPECT_EQ(ParamError(R"("integer n" [1.5])"),
              "p.pbrt:1:25: error: parameter \"n\": expected integers, got 1.5");
    EXPECT_EQ(ParamError(R"("integer n" [1e12])"),
              "p.pbrt:1:25: error: parameter \"n\": expected integers, got 1e+12");
    EXPECT_EQ(ParamError(R"("point P" [0 0 0 1])"),
              "p.pbrt:1:25: error: parameter \"P\": expected a multiple of 3 values, got 4");
    EXPECT_EQ(ParamError(R"("rgb Kd" [1 1])"),
              "p.pbrt:1:25: error: parameter \"Kd\": expected a multiple of 3 values, got 2");
    EXPECT_EQ(ParamError(R"("bool b" "yes")"),
              "p.pbrt:1:25: error: parameter \"b\": expected \"true\" or \"false\", got \"yes\"");
    EXPECT_EQ(ParamError(R"("quaternion q" [1 0 0 0])"),
              "p.pbrt:1:25: error: unknown parameter type \"quaternion\"");
    EXPECT_EQ(ParamError(R"("floatradius" 1)"),
              "p.pbrt:1:25: error: invalid parameter declaration \"floatradius\" "
              "(expected \"type name\")");
    EXPECT_EQ(ParamError(R"("float radius" [1 "a"])"),
              "p.pbrt:1:25: error: parameter \"radius\": cannot mix numbers and strings");
    EXPECT_EQ(ParamError(R"("float radius" Shape "x")"),
              "p.pbrt:1:25: error: parameter \"radius\" has no value");
    EXPECT_EQ(ParamError(R"("float radius" [1 2)"),
              "p.pbrt:1:40: error: missing \"]\" for parameter \"radius\"");
    EXPECT_EQ(ParamError(R"("blackbody L" [0 1])"),
              "p.pbrt:1:25: error: parameter \"L\": blackbody temperature must be positive");
}

}  // namespace
}  // namespace prism
