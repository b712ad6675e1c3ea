// Catmull–Rom splines (render/spline.h): weights reproduce the segments, integrals and inverses
// are exact for what the spline represents exactly (cubics inside, by their end differences),
// and 2-D sampling draws from the density it reports.
#include "render/spline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"

namespace prism {
namespace {

// Uneven nodes on [0, 2].
std::vector<float> Nodes() { return {0.f, 0.1f, 0.3f, 0.45f, 0.8f, 1.f, 1.4f, 1.5f, 2.f}; }

TEST(Spline, WeightsReproduceTheSegments) {
    const std::vector<float> x = Nodes();
    std::vector<float> f;
    for (float v : x) f.push_back(std::sin(3 * v) + v);
    for (float v : {0.f, 0.05f, 0.31f, 0.7f, 1.45f, 1.99f, 2.f}) {
        int off;
        float w[4];
        ASSERT_TRUE(CatmullRomWeights(x, v, &off, w)) << v;
        double sum = 0;
        for (int k = 0; k < 4; ++k)
            if (w[k] != 0) sum += double(w[k]) * f[size_t(off + k)];
        const int i = std::min(int(std::upper_bound(x.begin(), x.end(), v) - x.begin()) - 1, 7);
        const SplineSegment s = SplineSegmentAt(x, f.data(), i);
        EXPECT_NEAR(sum, s.Value((v - x[size_t(i)]) / s.width), 1e-5) << v;
    }
    int off;
    float w[4];
    EXPECT_FALSE(CatmullRomWeights(x, -0.01f, &off, w));
    EXPECT_FALSE(CatmullRomWeights(x, 2.01f, &off, w));
}

TEST(Spline, IntegralsAndInversesAreExactForALine) {
    // A line is its own spline (central differences of a line are its slope).
    const std::vector<float> x = Nodes();
    std::vector<float> f, cdf(x.size());
    for (float v : x) f.push_back(0.5f + 2 * v);
    const double total = IntegrateCatmullRom(x.data(), int(x.size()), f.data(), cdf.data());
    EXPECT_NEAR(total, 5.0, 1e-5);  // ∫0^2 (0.5 + 2x) dx
    for (size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(cdf[i], 0.5 * x[i] + x[i] * x[i], 1e-5) << i;
    // The inverse of the increasing line, clamped at its ends.
    for (float u : {0.6f, 1.f, 2.2f, 4.4f})
        EXPECT_NEAR(InvertCatmullRom(x.data(), int(x.size()), f.data(), u), (u - 0.5f) / 2, 1e-5)
            << u;
    EXPECT_EQ(InvertCatmullRom(x.data(), int(x.size()), f.data(), 0.f), 0.f);
    EXPECT_EQ(InvertCatmullRom(x.data(), int(x.size()), f.data(), 9.f), 2.f);
}

TEST(Spline, TwoDimensionalSamplesFollowTheirDensity) {
    // Rows at three alphas, each a bump at a different place; sample between rows.
    const std::vector<float> alpha = {0.f, 0.5f, 1.f}, x = Nodes();
    const int n = int(x.size());
    std::vector<float> values, cdf(size_t(3 * n));
    for (float a : alpha)
        for (float v : x) values.push_back(std::exp(-8 * (v - 0.5f - a) * (v - 0.5f - a)) + 0.05f);
    for (int r = 0; r < 3; ++r)
        IntegrateCatmullRom(x.data(), n, &values[size_t(r * n)], &cdf[size_t(r * n)]);
    const float a = 0.3f;
    // Histogram of samples against the reported density integrated over each bin.
    constexpr int Bins = 20, N = 200000;
    std::vector<double> hist(Bins, 0);
    PCG32 rng(7);
    for (int k = 0; k < N; ++k) {
        float value, pdf;
        const float s = SampleCatmullRom2D(alpha.data(), 3, x.data(), n, values.data(), cdf.data(),
                                           a, rng.Uniform(), &value, &pdf);
        ASSERT_TRUE(s >= 0 && s <= 2) << s;
        hist[size_t(std::min(int(s / 2 * Bins), Bins - 1))] += 1.0 / N;
    }
    // The density the sampler reports, by quadrature (pdf at points via u that lands there is
    // awkward; the interpolated row over its integral instead).
    auto row = [&](float v) {
        int off;
        float wa[4], wx[4];
        EXPECT_TRUE(CatmullRomWeights(alpha, a, &off, wa));
        double sum = 0;
        for (int i = 0; i < 4; ++i) {
            if (wa[i] == 0) continue;
            const float *r = &values[size_t((off + i) * n)];
            int ox;
            if (!CatmullRomWeights(x, v, &ox, wx)) return 0.0;
            for (int j = 0; j < 4; ++j)
                if (wx[j] != 0) sum += double(wa[i]) * wx[j] * r[ox + j];
        }
        return sum;
    };
    double total = 0;
    std::vector<double> expect(Bins, 0);
    for (int q = 0; q < 20000; ++q) {
        const float v = 2 * (q + 0.5f) / 20000;
        expect[size_t(std::min(int(v / 2 * Bins), Bins - 1))] += row(v);
        total += row(v);
    }
    for (int b = 0; b < Bins; ++b)
        EXPECT_NEAR(hist[size_t(b)], expect[size_t(b)] / total, 0.004) << b;
    // Outside the rows' range there is nothing to sample.
    EXPECT_TRUE(std::isnan(
        SampleCatmullRom2D(alpha.data(), 3, x.data(), n, values.data(), cdf.data(), 1.5f, 0.5f)));
}

}  // namespace
}  // namespace prism
