// pbrt-v3's tabulated BSDF (render/fourier_bsdf.h) on tables written here: a Lambertian table
// reproduces the Lambertian BSDF and its cosine density, a glossy coloured table's sampling
// follows the density it reports (its albedo estimate matches quadrature), broken files are
// refused with what is wrong, and the material reads its file as a scene names it.
#include "render/fourier_bsdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "core/rng.h"
#include "render/bsdf.h"
#include "render/fourier_material.h"
#include "support/bsdf_file.h"
#include "support/render_text.h"
#include "support/sphere_quadrature.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using test::DirectionAt;

// A glossy, coloured table on uneven cosines: a lobe about the mirror direction that narrows
// towards grazing, a little transmission, three channels (luminance, red, blue).
std::string GlossyTable() {
    std::vector<float> mu;
    for (int i = 0; i < 33; ++i) mu.push_back(float(std::sin(Pi / 2 * (-1 + 2 * i / 32.0))));
    const int order = 8;
    return test::FourierBsdfBytes(mu, 3, order, 1.5f, [&](float muI, float muO) {
        std::vector<float> a(3 * order, 0.f);
        const bool reflect = muI * muO < 0;
        const float base = reflect ? 0.25f * std::abs(muI) : 0.02f * std::abs(muI);
        for (int k = 0; k < order; ++k) {
            const float lobe = base * std::exp(-0.15f * k * k) * (reflect ? 1 + std::abs(muO) : 1);
            a[size_t(k)] = lobe;                     // luminance
            a[size_t(order + k)] = 1.2f * lobe;      // red
            a[size_t(2 * order + k)] = 0.6f * lobe;  // blue
        }
        return a;
    });
}

TEST(FourierBsdf, ALambertianTableIsLambertian) {
    const FourierTable t = FourierTable::Parse(test::LambertianFourierBsdf(0.6f), "lambert");
    const FourierLobe l{&t};
    for (float muO : {0.9f, 0.5f, -0.7f}) {
        const Vec3f wo = DirectionAt(muO, 0.3f);
        for (float c : {0.8f, 0.4f, 0.2f}) {
            const Vec3f wi = DirectionAt(muO > 0 ? c : -c, 2.f);  // reflection, on wo's side
            EXPECT_NEAR(l.f(wo, wi).g, 0.6f / float(Pi), 2e-4f) << muO << " " << c;
            EXPECT_NEAR(l.Pdf(wo, wi), c / float(Pi), 2e-3f);
            EXPECT_EQ(l.f(wo, Vec3f(wi.x, wi.y, -wi.z)).g, 0.f);  // no transmission
        }
        EXPECT_NEAR(l.AlbedoEstimate(wo), 0.6f, 2e-3f);
    }
}

TEST(FourierBsdf, SamplesFollowTheirDensity) {
    const FourierTable t = FourierTable::Parse(GlossyTable(), "glossy");
    ASSERT_EQ(t.NumChannels(), 3);
    const FourierLobe l{&t};
    PCG32 rng(9);
    for (float muO : {0.95f, 0.6f, 0.2f, -0.5f}) {
        const Vec3f wo = DirectionAt(muO, 1.f);
        const RGB albedo = test::IntegrateSphere(
            [&](const Vec3f &wi) { return l.f(wo, wi) * std::abs(wi.z); }, 600);
        const RGB pdfNorm =
            test::IntegrateSphere([&](const Vec3f &wi) { return RGB(l.Pdf(wo, wi)); }, 600);
        EXPECT_NEAR(pdfNorm.g, 1, 0.01f) << muO;
        RGB estimate;
        const int n = 100000;
        for (int i = 0; i < n; ++i) {
            Vec3f wi;
            float pdf;
            if (!l.Sample(wo, {rng.Uniform(), rng.Uniform()}, &wi, &pdf)) continue;
            ASSERT_NEAR(pdf, l.Pdf(wo, wi), 1e-3f * pdf + 1e-5f);
            estimate += l.f(wo, wi) * (std::abs(wi.z) / pdf);
        }
        estimate = estimate / float(n);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(estimate[k], albedo[k], 0.015f * albedo[k]) << muO;
            EXPECT_NEAR(l.Albedo(wo)[k], albedo[k], 0.01f * albedo[k]) << muO;  // the AOV's
        }
        EXPECT_GT(albedo.r, albedo.b);
    }
}

TEST(FourierBsdf, BrokenFilesAreRefusedWithWhatIsWrong) {
    const std::string good = test::LambertianFourierBsdf(0.5f, 5);
    auto message = [](const std::string &bytes) -> std::string {
        try {
            FourierTable::Parse(bytes, "\"x.bsdf\"");
        } catch (const std::runtime_error &e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(message("hello").find("header"), std::string::npos);
    EXPECT_NE(message(good.substr(0, good.size() - 4)).find("truncated"), std::string::npos);
    std::string bad = good;
    bad[24] = 2;  // two channels
    EXPECT_NE(message(bad).find("channels"), std::string::npos);
    bad = good;
    const size_t entries = 64 + 4 * (5 + 25);  // the first entry's offset
    bad[entries] = char(100);
    EXPECT_NE(message(bad).find("past the coefficients"), std::string::npos);
    bad = good;
    bad[64 + 3] = char(0x40);  // the first cosine becomes 2
    EXPECT_NE(message(bad).find("increasing"), std::string::npos);
    EXPECT_EQ(message(good), "");
}

// Random corruptions of a valid table (bytes flipped, the file cut short): each is refused
// with a runtime_error or read into a table every lookup of which stays in bounds (the
// sanitizer build checks the second) and gives finite, non-negative values.
TEST(FourierBsdf, CorruptedFilesAreRefusedOrReadSafely) {
    const std::string good = test::LambertianFourierBsdf(0.5f, 7);
    PCG32 rng(3);
    int refused = 0, read = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        std::string bytes = good;
        const int flips = 1 + int(rng.Uniform() * 4);
        for (int k = 0; k < flips; ++k)
            bytes[size_t(rng.Uniform() * float(bytes.size()))] = char(rng.Next() & 0xff);
        if (trial % 10 == 0) bytes.resize(size_t(rng.Uniform() * float(bytes.size())));
        try {
            const FourierTable t = FourierTable::Parse(bytes, "x");
            const FourierLobe l{&t};
            ++read;
            for (int k = 0; k < 8; ++k) {
                const Vec3f wo = DirectionAt(-1 + 2 * rng.Uniform(), 6 * rng.Uniform());
                const Vec3f wi = DirectionAt(-1 + 2 * rng.Uniform(), 6 * rng.Uniform());
                const RGB f = l.f(wo, wi);
                EXPECT_TRUE(f.IsFinite() && f.r >= 0 && f.g >= 0 && f.b >= 0);
                EXPECT_GE(l.Pdf(wo, wi), 0.f);
                Vec3f s;
                float pdf;
                if (l.Sample(wo, {rng.Uniform(), rng.Uniform()}, &s, &pdf))
                    EXPECT_TRUE(pdf > 0 && std::isfinite(pdf));
            }
        } catch (const std::runtime_error &) {
            ++refused;
        }
    }
    EXPECT_GT(refused, 100);
    EXPECT_GT(read, 100);
}

TEST(FourierMaterial, ReadsItsFileAsTheSceneNamesIt) {
    const auto dir = test::ScratchDir("fourier_material");
    std::ofstream(dir / "lambert.bsdf", std::ios::binary) << test::LambertianFourierBsdf(0.5f);
    Diagnostics diag;
    RenderScene keep;
    const std::string file = (dir / "lambert.bsdf").string();
    const Material &m = test::BuildSphereMaterial(
        "Material \"fourier\" \"string bsdffile\" \"" + file + "\"\n", diag, keep);
    ASSERT_TRUE(m.ModelAs<FourierMaterial>());
    EXPECT_EQ(diag.Count(), size_t(0));
    SurfaceInteraction si;
    si.n = si.ns = {0, 0, 1};
    si.dpdu = {1, 0, 0};
    const BSDF b = m.GetBSDF(si, {});
    EXPECT_NEAR(b.f(DirectionAt(0.7f, 0), DirectionAt(0.5f, 2)).g, 0.5f / float(Pi), 2e-4f);

    for (const std::string &bad :
         {std::string("\"string bsdffile\" \"missing.bsdf\""),
          std::string("\"string bsdffile\" \"") + (dir / "lambert.bsdf").string() + "x\"",
          std::string("")}) {
        try {
            test::BuildSphereMaterial("Material \"fourier\" " + bad + "\n", diag, keep);
            ADD_FAILURE() << bad;
        } catch (const SceneError &e) {
            EXPECT_NE(std::string(e.what()).find("test.pbrt:4:"), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace prism
