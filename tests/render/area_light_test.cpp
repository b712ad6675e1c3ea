// Textured area lights (glTF emissive textures): the irradiance their light samples estimate
// below a unit square emitter matches the analytic form factor, a half-black texture gives half
// of it, triangles whose texture is black are never sampled, and PdfArea is the density the
// samples are drawn with.
#include "render/area_light.h"

#include <gtest/gtest.h>

#include <cmath>

namespace prism {
namespace {

// Irradiance at a point at distance c below the corner of an a x b rectangle of radiance 1,
// facing it: pi times the form factor of a differential area parallel to the rectangle.
double CornerIrradiance(double a, double b, double c) {
    const double A = a / c, B = b / c, sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
    return 0.5 * (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb));
}

// u < 0.5: black, else white (a step in the first uv set's u).
class StepTexture final : public Texture {
  public:
    RGB Evaluate(const TextureContext &c) const override { return RGB(c.uv.x < 0.5f ? 0.f : 1.f); }
};

// The square [0,1]^2 at z = 1, facing down (-z), as two quads split at x = 0.5 (four
// triangles); uv = (x, y).
std::unique_ptr<TriangleMesh> Emitter() {
    std::vector<Vec3f> P = {{0, 0, 1},    {0.5f, 0, 1}, {0.5f, 1, 1}, {0, 1, 1},
                            {0.5f, 0, 1}, {1, 0, 1},    {1, 1, 1},    {0.5f, 1, 1}};
    std::vector<Vec2f> uv;
    for (const Vec3f &p : P) uv.emplace_back(p.x, p.y);
    // Clockwise seen from below: (p1 - p0) x (p2 - p0) points down.
    std::vector<uint32_t> idx = {0, 2, 1, 0, 3, 2, 4, 6, 5, 4, 7, 6};
    return std::make_unique<TriangleMesh>(Transform(), false, P, idx, std::vector<Vec3f>{}, uv);
}

// E at (0.5, 0.5, 0) facing up, from n stratified light samples.
double Irradiance(const DiffuseAreaLight &light, int n) {
    SurfaceInteraction si;
    si.p = Vec3f(0.5f, 0.5f, 0);
    si.n = si.ns = Vec3f(0, 0, 1);
    double E = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            LightSample ls;
            Vec2f u((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n));
            if (!light.SampleLi(si, u, &ls)) continue;
            E += double(ls.Li.g) * std::max(0.f, ls.wi.z) / ls.pdf;
        }
    return E / (double(n) * n);
}

TEST(TexturedAreaLight, UniformTextureMatchesTheFormFactor) {
    const double expected = 4 * CornerIrradiance(0.5, 0.5, 1);  // L = 1
    auto mesh = Emitter();
    DiffuseAreaLight constant(nullptr, mesh.get(), RGB(1), false, 1);
    DiffuseAreaLight textured(nullptr, mesh.get(), RGB(0.5f), false, 1,
                              std::make_shared<ConstantTexture>(RGB(2)));
    EXPECT_TRUE(textured.Textured());
    EXPECT_NEAR(Irradiance(constant, 256), expected, 2e-3 * expected);
    EXPECT_NEAR(Irradiance(textured, 256), expected, 2e-3 * expected);
    EXPECT_EQ(textured.SampledTriangles(), 4);
}

TEST(TexturedAreaLight, HalfBlackTextureGivesHalfTheLightAndSkipsItsTriangles) {
    const double full = 4 * CornerIrradiance(0.5, 0.5, 1);
    auto mesh = Emitter();
    DiffuseAreaLight half(nullptr, mesh.get(), RGB(1), false, 1, std::make_shared<StepTexture>());
    EXPECT_NEAR(Irradiance(half, 256), 0.5 * full, 2e-3 * full);
    // The left quad is black: its two triangles are never sampled.
    EXPECT_EQ(half.SampledTriangles(), 2);
    EXPECT_EQ(half.PdfArea(0), 0);
    EXPECT_EQ(half.PdfArea(1), 0);
    // The right quad (area 1/2) takes every sample, uniformly by area.
    EXPECT_NEAR(half.PdfArea(2), 2.0, 1e-9);
    EXPECT_NEAR(half.PdfArea(3), 2.0, 1e-9);
    // Every sample lands on a white point: none is wasted.
    SurfaceInteraction si;
    si.p = Vec3f(0.5f, 0.5f, 0);
    si.n = si.ns = Vec3f(0, 0, 1);
    for (int i = 0; i < 64; ++i) {
        LightSample ls;
        ASSERT_TRUE(half.SampleLi(si, Vec2f((float(i) + 0.5f) / 64, 0.37f), &ls));
        EXPECT_GE(ls.pLight.x, 0.5f - 1e-6f);
        EXPECT_EQ(ls.Li.g, 1.f);
    }
    // The untextured light: 1 / area everywhere.
    DiffuseAreaLight constant(nullptr, mesh.get(), RGB(1), false, 1);
    EXPECT_NEAR(constant.PdfArea(0), 1.0, 1e-9);
}

TEST(TexturedAreaLight, HitRadianceReadsTheTextureOnTheFrontOnly) {
    auto mesh = Emitter();
    DiffuseAreaLight half(nullptr, mesh.get(), RGB(3), false, 1, std::make_shared<StepTexture>());
    SurfaceInteraction si;
    si.n = Vec3f(0, 0, -1);
    si.uv = si.uv1 = Vec2f(0.75f, 0.5f);
    EXPECT_EQ(half.L(si, Vec3f(0, 0, -1)).g, 3.f);
    EXPECT_EQ(half.L(si, Vec3f(0, 0, 1)).g, 0.f);  // the back
    si.uv = Vec2f(0.25f, 0.5f);
    EXPECT_EQ(half.L(si, Vec3f(0, 0, -1)).g, 0.f);
}

TEST(TexturedAreaLight, MeanSamplesGrowWithTheUvFootprint) {
    EXPECT_EQ(DiffuseAreaLight::TextureMeanSamples(0), 1);
    EXPECT_EQ(DiffuseAreaLight::TextureMeanSamples(1e-7), 1);
    EXPECT_EQ(DiffuseAreaLight::TextureMeanSamples(0.5), 256);  // capped
    const int mid = DiffuseAreaLight::TextureMeanSamples(1.0 / 15000);
    EXPECT_GT(mid, 1);
    EXPECT_LT(mid, 256);
}

}  // namespace
}  // namespace prism
