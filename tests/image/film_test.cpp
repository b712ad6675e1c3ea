// Tests for pixel filters, sample splatting, tile merging and the NaN guard.
#include "image/film.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

namespace prism {
namespace {

Bounds2i Full(int w, int h) { return {{0, 0}, {w, h}}; }

bool BitEqual(const Image &a, const Image &b) {
    return a.width == b.width && a.height == b.height && a.channels == b.channels &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

// A deterministic stream of samples over a region: n per pixel at random offsets.
struct Sample {
    Vec2f p;
    RGB L;
};
std::vector<Sample> RandomSamples(const Bounds2i &b, int n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    std::vector<Sample> s;
    for (int y = b.pMin.y; y < b.pMax.y; ++y)
        for (int x = b.pMin.x; x < b.pMax.x; ++x)
            for (int i = 0; i < n; ++i)
                s.push_back({{float(x) + u(rng), float(y) + u(rng)},
                             RGB(u(rng) * 10.f, u(rng), u(rng) * 0.1f)});
    return s;
}

// Renders `samples` tile by tile (tiles of `tileSize`, samples assigned to the tile containing
// their pixel), merging in tile order.
Image RenderTiled(const Film &proto, const std::vector<Sample> &samples, int tileSize) {
    Film film(proto.FullResolution(), proto.PixelBounds(), proto.GetFilter());
    const Bounds2i &pb = film.PixelBounds();
    for (int ty = pb.pMin.y; ty < pb.pMax.y; ty += tileSize) {
        for (int tx = pb.pMin.x; tx < pb.pMax.x; tx += tileSize) {
            Bounds2i tb{{tx, ty},
                        {std::min(tx + tileSize, pb.pMax.x), std::min(ty + tileSize, pb.pMax.y)}};
            FilmTile tile = film.MakeTile(tb);
            for (const Sample &s : samples)
                if (tb.Inside({int(std::floor(s.p.x)), int(std::floor(s.p.y))}))
                    tile.AddSample(s.p, s.L);
            film.MergeTile(tile);
        }
    }
    return film.ToImage();
}

// The same through TiledFilm: reused tile buffers, tiles merged in order, `skip` not rendered.
Image RenderStreamed(const Film &proto, const std::vector<Sample> &samples, int tileSize,
                     int skip = -1) {
    TiledFilm film(proto.FullResolution(), proto.PixelBounds(), proto.GetFilter(), tileSize);
    FilmTile tile;
    for (int t = 0; t < film.NumTiles(); ++t) {
        if (t == skip) {
            film.MergeNext(nullptr);
            continue;
        }
        Bounds2i tb = film.TilePixels(t);
        film.ResetTile(t, &tile);
        for (const Sample &s : samples)
            if (tb.Inside({int(std::floor(s.p.x)), int(std::floor(s.p.y))}))
                tile.AddSample(s.p, s.L);
        film.MergeNext(&tile);
    }
    return film.Finish();
}

TEST(TiledFilm, BitIdenticalToFilmMergingInOrder) {
    const Filter filters[] = {MakeBoxFilter(), MakeGaussianFilter(2.f), MakeTriangleFilter(1.f),
                              MakeMitchellFilter(2.5f), MakeBoxFilter(3.7f)};
    const Bounds2i crops[] = {Full(37, 29), {{3, 5}, {30, 26}}};
    for (const Filter &f : filters) {
        for (const Bounds2i &crop : crops) {
            Film proto({37, 29}, crop, f);
            auto samples = RandomSamples(proto.PixelBounds(), 3, 7);
            for (int tileSize : {1, 4, 16, 64}) {
                Image a = RenderTiled(proto, samples, tileSize);
                Image b = RenderStreamed(proto, samples, tileSize);
                EXPECT_TRUE(BitEqual(a, b)) << "tile size " << tileSize;
            }
        }
    }
}

TEST(TiledFilm, SkippedTileContributesNothing) {
    Film proto({20, 20}, Full(20, 20), MakeGaussianFilter(2.f));
    auto samples = RandomSamples(proto.PixelBounds(), 1, 3);
    // Tile 3 of 4 (pixels [0,10) x [10,20)) not rendered: the same as dropping its samples.
    std::vector<Sample> kept;
    for (const Sample &s : samples)
        if (!(s.p.x < 10 && s.p.y >= 10)) kept.push_back(s);
    EXPECT_TRUE(BitEqual(RenderTiled(proto, kept, 10), RenderStreamed(proto, samples, 10, 2)));
}

// Through TiledFilm with tiles resolved in place (the render's path for the box filter), the
// tiles resolved in a scrambled order as threads finish them; `skip` not rendered.
Image RenderInPlace(const Film &proto, const std::vector<Sample> &samples, int tileSize,
                    int skip = -1) {
    TiledFilm film(proto.FullResolution(), proto.PixelBounds(), proto.GetFilter(), tileSize);
    EXPECT_TRUE(film.EnableResolveInPlace());
    std::vector<int> order(size_t(film.NumTiles()));
    for (size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    std::shuffle(order.begin(), order.end(), std::mt19937(5));
    FilmTile tile;
    for (int t : order) {
        if (t == skip) continue;
        Bounds2i tb = film.TilePixels(t);
        film.ResetTile(t, &tile);
        EXPECT_EQ(tile.PixelBounds(), tb);  // no border: just the tile's pixels
        for (const Sample &s : samples)
            if (tb.Inside({int(std::floor(s.p.x)), int(std::floor(s.p.y))}))
                tile.AddSample(s.p, s.L);
        film.ResolveTile(t, tile);
    }
    return film.Finish();
}

// Samples that lie in the pixel they were drawn for (render/sampler.h FilmPosition): those
// that float rounding put on the next pixel's edge are dropped.
std::vector<Sample> InPixelSamples(const Bounds2i &b, int n, uint32_t seed) {
    std::vector<Sample> in;
    for (const Sample &s : RandomSamples(b, n, seed)) {
        const float fx = std::floor(s.p.x), fy = std::floor(s.p.y);
        if (s.p.x - fx < 1 && s.p.y - fy < 1) in.push_back(s);
    }
    return in;
}

TEST(TiledFilm, ResolvedInPlaceBitIdenticalToMergedTiles) {
    const Bounds2i crops[] = {Full(37, 29), {{3, 5}, {30, 26}}};
    for (const Bounds2i &crop : crops) {
        Film proto({37, 29}, crop, MakeBoxFilter());
        auto samples = InPixelSamples(proto.PixelBounds(), 3, 11);
        for (int tileSize : {1, 4, 16, 64}) {
            Image merged = RenderStreamed(proto, samples, tileSize);
            EXPECT_TRUE(BitEqual(RenderInPlace(proto, samples, tileSize), merged))
                << "tile size " << tileSize;
        }
        // A tile not rendered (a cancelled render) is black, as when merged.
        EXPECT_TRUE(
            BitEqual(RenderInPlace(proto, samples, 10, 2), RenderStreamed(proto, samples, 10, 2)));
    }
}

TEST(TiledFilm, ResolvesInPlaceOnlyForTheUnitBoxWithoutNoise) {
    auto inPlace = [](const Filter &f, bool noise) {
        TiledFilm film({16, 16}, Full(16, 16), f, 8);
        if (noise) film.EnableNoiseEstimate();
        return film.EnableResolveInPlace();
    };
    EXPECT_TRUE(inPlace(MakeBoxFilter(), false));
    EXPECT_FALSE(inPlace(MakeBoxFilter(), true));
    EXPECT_FALSE(inPlace(MakeBoxFilter(1.f), false));
    EXPECT_FALSE(inPlace(MakeGaussianFilter(2.f), false));
    // Without the caller's promise, tiles keep their border and merge in order.
    TiledFilm film({16, 16}, Full(16, 16), MakeBoxFilter(), 8);
    EXPECT_FALSE(film.ResolvesTiles());
    FilmTile tile;
    film.ResetTile(0, &tile);
    EXPECT_EQ(tile.PixelBounds(), Bounds2i({0, 0}, {9, 9}));
}

// A pixel's samples added at once (the render's path for the box filter) sum exactly as
// when added one by one, NaN samples included (counted, added as 0, with their weight).
TEST(FilmTile, AddPixelSamplesMatchesAddSample) {
    Film film({8, 8}, Full(8, 8), MakeBoxFilter());
    auto samples = InPixelSamples(Full(8, 8), 5, 13);
    samples[7].L = RGB(std::nanf(""), 1.f, 2.f);
    FilmTile one = film.MakeTile(Full(8, 8)), all = film.MakeTile(Full(8, 8));
    ASSERT_TRUE(all.UnitBox());
    for (const Sample &s : samples) one.AddSample(s.p, s.L);
    for (size_t i = 0; i < samples.size();) {
        const Vec2i p(int(std::floor(samples[i].p.x)), int(std::floor(samples[i].p.y)));
        std::vector<RGB> L;
        for (; i < samples.size() && int(std::floor(samples[i].p.x)) == p.x &&
               int(std::floor(samples[i].p.y)) == p.y;
             ++i)
            L.push_back(samples[i].L);
        all.AddPixelSamples(p, L.data(), int(L.size()));
    }
    ASSERT_EQ(one.Sums().size(), all.Sums().size());
    EXPECT_EQ(
        std::memcmp(one.Sums().data(), all.Sums().data(), one.Sums().size() * sizeof(FilmPixel)),
        0);
    EXPECT_EQ(all.NonFinite().count, 1u);
    EXPECT_EQ(one.NonFinite().firstPixel, all.NonFinite().firstPixel);
    EXPECT_FALSE(Film({8, 8}, Full(8, 8), MakeGaussianFilter()).MakeTile(Full(8, 8)).UnitBox());
}

TEST(Filter, Values) {
    Filter box = MakeBoxFilter();
    EXPECT_EQ(box.Evaluate(0.f, 0.f), 1.f);
    EXPECT_EQ(box.Evaluate(0.5f, -0.5f), 1.f);
    EXPECT_EQ(box.Evaluate(0.51f, 0.f), 0.f);

    Filter g = MakeGaussianFilter(2.f, 2.f);
    float e = std::exp(-2.f * 4.f);
    EXPECT_FLOAT_EQ(g.Evaluate(0, 0), (1 - e) * (1 - e));
    EXPECT_FLOAT_EQ(g.Evaluate(1, 0.5f), (std::exp(-2.f) - e) * (std::exp(-0.5f) - e));
    EXPECT_EQ(g.Evaluate(2.f, 0), 0.f);
    EXPECT_EQ(g.Evaluate(2.5f, 0), 0.f);

    Filter t = MakeTriangleFilter(2.f);
    EXPECT_FLOAT_EQ(t.Evaluate(0, 0), 4.f);
    EXPECT_FLOAT_EQ(t.Evaluate(1.5f, -1), 0.5f);
    EXPECT_EQ(t.Evaluate(0, 3), 0.f);

    Filter m = MakeMitchellFilter(2.f);
    float b = 1.f / 3;
    float m0 = (6 - 2 * b) / 6;
    EXPECT_FLOAT_EQ(m.Evaluate(0, 0), m0 * m0);
    // pbrt-v3 scales the offset by 1/radius before the cubic on [0, 2]: d = r is x = 2.
    EXPECT_NEAR(m.Evaluate(2.f, 0), 0.f, 1e-6f);
    // At d = r/2 (x = 1) the inner cubic gives (12 - 9B - 6C - 18 + 12B + 6C + 6 - 2B) / 6 = B / 6.
    EXPECT_NEAR(m.Evaluate(1.f, 0) / m0, b / 6, 1e-6f);
    // Negative lobe between x = 1 and 2.
    EXPECT_LT(m.Evaluate(1.5f, 0), 0.f);

    // pbrt's "sinc": sin(pi d)/(pi d) sin(pi d/tau)/(pi d/tau) within the radius.
    Filter s = MakeLanczosSincFilter(4.f, 3.f);
    EXPECT_FLOAT_EQ(s.Evaluate(0, 0), 1.f);
    const double pi = 3.14159265358979323846;
    auto ref = [&](double d) {
        return std::sin(pi * d) / (pi * d) * std::sin(pi * d / 3) / (pi * d / 3);
    };
    for (float d : {0.25f, 0.5f, 1.5f, 2.5f, 3.9f})
        EXPECT_NEAR(s.Evaluate(d, 0), ref(d), 1e-6) << d;
    EXPECT_NEAR(s.Evaluate(1.f, 0), 0.f, 1e-6f);  // sinc's first zero
    EXPECT_LT(s.Evaluate(1.5f, 0), 0.f);          // its negative lobe
    EXPECT_NEAR(s.Evaluate(0.5f, 0.5f), ref(0.5) * ref(0.5), 1e-6);
    EXPECT_EQ(s.Evaluate(4.5f, 0), 0.f);
}

TEST(Film, BoxFilterReproducesValuesExactly) {
    Film film({7, 5}, Full(7, 5), MakeBoxFilter());
    FilmTile tile = film.MakeTile(film.PixelBounds());
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    std::vector<RGB> expect;
    for (int y = 0; y < 5; ++y) {
        for (int x = 0; x < 7; ++x) {
            RGB L(u(rng) * 3.f, std::ldexp(u(rng), -20), 1e7f * u(rng));
            expect.push_back(L);
            // Anywhere inside the pixel, including its top-left corner.
            Vec2f p = (x + y) % 3 == 0 ? Vec2f(float(x), float(y))
                                       : Vec2f(float(x) + u(rng), float(y) + u(rng));
            tile.AddSample(p, L);
        }
    }
    film.MergeTile(tile);
    Image img = film.ToImage();
    ASSERT_EQ(img.width, 7);
    ASSERT_EQ(img.height, 5);
    ASSERT_EQ(img.channels, 3);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x) EXPECT_EQ(img.GetRGB(x, y), expect[size_t(y * 7 + x)]);
}

TEST(Film, BoxFilterAveragesSamples) {
    Film film({2, 1}, Full(2, 1), MakeBoxFilter());
    FilmTile tile = film.MakeTile(film.PixelBounds());
    for (float v : {1.f, 2.f, 3.f, 6.f}) tile.AddSample({0.3f, 0.7f}, RGB(v));
    film.MergeTile(tile);
    Image img = film.ToImage();
    EXPECT_EQ(img.GetRGB(0, 0), RGB(3.f));
    EXPECT_EQ(img.GetRGB(1, 0), RGB(0.f));  // no samples: zero weight -> 0
}

TEST(Film, SampleOnPixelBoundaryLandsInOnePixel) {
    Film film({4, 4}, Full(4, 4), MakeBoxFilter());
    FilmTile tile = film.MakeTile(film.PixelBounds());
    tile.AddSample({2.f, 1.f}, RGB(5.f));  // the corner shared by pixels (1..2, 0..1)
    film.MergeTile(tile);
    Image img = film.ToImage();
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            EXPECT_EQ(img.GetRGB(x, y), (x == 2 && y == 1) ? RGB(5.f) : RGB(0.f)) << x << "," << y;

    // A wider box: x = 1.5 is the centre of pixel 1; the half-open support [c - 1, c + 1)
    // takes pixels 1 and 2 (centres 1.5, 2.5) but not 0 (centre 0.5, offset exactly 1).
    Film wide({4, 1}, Full(4, 1), MakeBoxFilter(1.f));
    FilmTile t2 = wide.MakeTile(wide.PixelBounds());
    t2.AddSample({1.5f, 0.5f}, RGB(1.f));
    wide.MergeTile(t2);
    Image w = wide.ToImage();
    EXPECT_EQ(w.GetRGB(0, 0), RGB(0.f));
    EXPECT_EQ(w.GetRGB(1, 0), RGB(1.f));
    EXPECT_EQ(w.GetRGB(2, 0), RGB(1.f));
    EXPECT_EQ(w.GetRGB(3, 0), RGB(0.f));
}

// pbrt's default box (radius 1/2) takes a shortcut in AddSample: the sample goes to pixel
// floor(p) of the tile with weight 1. Checked against those sums computed here, for samples on
// pixel edges, just below them, outside the crop window and far away, through a cropped
// film's tiles.
TEST(Film, HalfPixelBoxAddsEachSampleToFloorPixel) {
    const Bounds2i crop{{1, 2}, {7, 6}};
    Film film({8, 8}, crop, MakeBoxFilter(0.5f));
    std::vector<Sample> samples = RandomSamples(Full(8, 8), 3, 7);
    for (float x : {0.f, 1.f, 3.f, std::nextafter(3.f, 0.f), 6.999999f, 7.f, -0.25f, 1e6f})
        for (float y : {2.f, std::nextafter(2.f, 0.f), 4.5f, 5.999999f, 6.f, -3e5f})
            samples.push_back({{x, y}, RGB(x + 2 * y, 1.f, 0.25f)});
    std::vector<double> sum(64 * 3, 0.0), weight(64, 0.0);
    for (const Sample &s : samples) {
        double fx = std::floor(double(s.p.x)), fy = std::floor(double(s.p.y));
        if (fx < crop.pMin.x || fx >= crop.pMax.x || fy < crop.pMin.y || fy >= crop.pMax.y)
            continue;
        int i = int(fy) * 8 + int(fx);
        sum[3 * i] += double(s.L.r);
        sum[3 * i + 1] += double(s.L.g);
        sum[3 * i + 2] += double(s.L.b);
        weight[i] += 1;
    }
    for (int tileSize : {2, 3, 16}) {
        Image img = RenderTiled(film, samples, tileSize);
        for (int y = crop.pMin.y; y < crop.pMax.y; ++y)
            for (int x = crop.pMin.x; x < crop.pMax.x; ++x) {
                int i = y * 8 + x;
                RGB c = img.GetRGB(x - crop.pMin.x, y - crop.pMin.y);
                ASSERT_GT(weight[i], 0);
                EXPECT_EQ(c.r, float(sum[3 * i] / weight[i])) << x << "," << y;
                EXPECT_EQ(c.g, float(sum[3 * i + 1] / weight[i])) << x << "," << y;
                EXPECT_EQ(c.b, float(sum[3 * i + 2] / weight[i])) << x << "," << y;
            }
    }
}

TEST(Film, SamplesOutsideTheFilmAreIgnored) {
    Film film({3, 3}, Full(3, 3), MakeGaussianFilter());
    FilmTile tile = film.MakeTile(film.PixelBounds());
    tile.AddSample({-100.f, 1.f}, RGB(1.f));
    tile.AddSample({1e30f, -1e30f}, RGB(1.f));
    tile.AddSample({3.f, 3.f}, RGB(2.f));  // far corner, reaches pixel (2, 2) only
    film.MergeTile(tile);
    Image img = film.ToImage();
    EXPECT_EQ(img.GetRGB(2, 2), RGB(2.f));
    EXPECT_EQ(img.GetRGB(0, 0), RGB(0.f));
    EXPECT_EQ(film.NonFiniteCount(), 0u);
}

TEST(Film, GaussianSplatsToNeighbours) {
    Filter g = MakeGaussianFilter(2.f, 2.f);
    Film film({9, 9}, Full(9, 9), g);
    FilmTile tile = film.MakeTile(film.PixelBounds());
    tile.AddSample({4.5f, 4.5f}, RGB(1.f, 2.f, 3.f));
    film.MergeTile(tile);
    Image img = film.ToImage();
    // Pixels whose centre is within 2 (exclusive: the gaussian is 0 at the radius) get the
    // sample's value (it is the only sample); all others have zero weight.
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 9; ++x) {
            bool reached = std::abs(x - 4) <= 1 && std::abs(y - 4) <= 1;
            EXPECT_EQ(img.GetRGB(x, y), reached ? RGB(1.f, 2.f, 3.f) : RGB(0.f)) << x << "," << y;
        }

    // Two samples: each pixel is the filter-weighted mean.
    Film f2({9, 1}, Full(9, 1), g);
    FilmTile t2 = f2.MakeTile(f2.PixelBounds());
    t2.AddSample({3.5f, 0.5f}, RGB(1.f));
    t2.AddSample({5.2f, 0.5f}, RGB(3.f));
    f2.MergeTile(t2);
    Image i2 = f2.ToImage();
    for (int x = 0; x < 9; ++x) {
        float c = float(x) + 0.5f;
        float w1 = g.Evaluate(c - 3.5f, 0.f), w2 = g.Evaluate(c - 5.2f, 0.f);
        float expect = w1 + w2 > 0 ? (w1 * 1.f + w2 * 3.f) / (w1 + w2) : 0.f;
        EXPECT_NEAR(i2.GetRGB(x, 0).r, expect, 1e-6f) << x;
    }
    EXPECT_GT(i2.GetRGB(4, 0).r, 1.5f);
    EXPECT_LT(i2.GetRGB(4, 0).r, 2.5f);
}

TEST(Film, MakeTileCoversFilterReach) {
    Film box({64, 64}, Full(64, 64), MakeBoxFilter());
    Bounds2i t = box.MakeTile({{16, 16}, {32, 32}}).PixelBounds();
    // One extra pixel at the far side for samples rounded onto the tile's far edge.
    EXPECT_EQ(t, Bounds2i({16, 16}, {33, 33}));
    Film gauss({64, 64}, Full(64, 64), MakeGaussianFilter(2.f));
    EXPECT_EQ(gauss.MakeTile({{16, 16}, {32, 32}}).PixelBounds(), Bounds2i({14, 14}, {34, 34}));
    // Clipped to the film.
    EXPECT_EQ(gauss.MakeTile({{0, 0}, {16, 16}}).PixelBounds(), Bounds2i({0, 0}, {18, 18}));
}

TEST(Film, TilesMergedInOrderMatchOneBigTile) {
    // Triangle filter, samples at quarter-pixel offsets and small dyadic radiance: every
    // product and partial sum is exact, so any dropped or duplicated splat across tile
    // borders shows up as a bit difference.
    Film film({37, 29}, Full(37, 29), MakeTriangleFilter(2.f));
    std::vector<Sample> samples;
    for (int y = 0; y < 29; ++y)
        for (int x = 0; x < 37; ++x)
            for (int i = 0; i < 2; ++i)
                samples.push_back({{float(x) + 0.25f * float((x + i) % 4),
                                    float(y) + 0.25f * float((y + 2 * i) % 4)},
                                   RGB(float((x * 7 + y * 3 + i) % 16), float(i), 0.5f)});
    Image big = RenderTiled(film, samples, 1000);
    for (int tileSize : {1, 5, 8, 16})
        EXPECT_TRUE(BitEqual(RenderTiled(film, samples, tileSize), big)) << tileSize;

    // Gaussian with arbitrary samples: equal up to double-precision summation order.
    Film gfilm({33, 21}, Full(33, 21), MakeGaussianFilter(2.f, 2.f));
    std::vector<Sample> gs = RandomSamples(gfilm.PixelBounds(), 3, 5);
    Image gbig = RenderTiled(gfilm, gs, 1000);
    Image gtiled = RenderTiled(gfilm, gs, 8);
    for (size_t i = 0; i < gbig.pixels.size(); ++i)
        EXPECT_NEAR(gtiled.pixels[i], gbig.pixels[i], 1e-6f * std::abs(gbig.pixels[i])) << i;
    // Some neighbour influence exists (not just a box).
    Film boxFilm({33, 21}, Full(33, 21), MakeBoxFilter());
    EXPECT_NE(gbig.pixels, RenderTiled(boxFilm, gs, 8).pixels);
}

TEST(Film, ResultDoesNotDependOnThreadSchedule) {
    Film proto({40, 24}, Full(40, 24), MakeMitchellFilter(2.f));
    std::vector<Sample> samples = RandomSamples(proto.PixelBounds(), 2, 11);
    Image reference = RenderTiled(proto, samples, 8);

    // Fill tiles concurrently, in reverse, then merge in tile order.
    Film film({40, 24}, Full(40, 24), MakeMitchellFilter(2.f));
    std::vector<Bounds2i> bounds;
    for (int ty = 0; ty < 24; ty += 8)
        for (int tx = 0; tx < 40; tx += 8) bounds.push_back({{tx, ty}, {tx + 8, ty + 8}});
    std::vector<FilmTile> tiles(bounds.size());
    std::vector<std::thread> threads;
    for (size_t k = bounds.size(); k-- > 0;) {
        threads.emplace_back([&, k] {
            FilmTile tile = film.MakeTile(bounds[k]);
            for (const Sample &s : samples)
                if (bounds[k].Inside({int(std::floor(s.p.x)), int(std::floor(s.p.y))}))
                    tile.AddSample(s.p, s.L);
            tiles[k] = std::move(tile);
        });
    }
    for (auto &t : threads) t.join();
    for (const FilmTile &t : tiles) film.MergeTile(t);
    EXPECT_TRUE(BitEqual(film.ToImage(), reference));
}

TEST(Film, NonFiniteSamplesAreCountedAndZeroed) {
    Film film({6, 4}, Full(6, 4), MakeBoxFilter());
    FilmTile a = film.MakeTile({{0, 0}, {3, 4}});
    FilmTile b = film.MakeTile({{3, 0}, {6, 4}});
    a.AddSample({1.5f, 1.5f}, RGB(1.f));
    a.AddSample({2.5f, 3.5f}, RGB(NAN, 0.f, 0.f));
    b.AddSample({4.5f, 1.5f}, RGB(0.f, INFINITY, 0.f));
    b.AddSample({5.5f, 2.5f}, RGB(2.f));
    b.AddSample({5.5f, 2.5f}, RGB(-INFINITY));
    // Merge b first: the report must still be the smallest (y, x) pixel.
    film.MergeTile(b);
    film.MergeTile(a);
    EXPECT_EQ(film.NonFiniteCount(), 3u);
    ASSERT_TRUE(film.FirstNonFinitePixel().has_value());
    EXPECT_EQ(*film.FirstNonFinitePixel(), Vec2i(4, 1));
    Image img = film.ToImage();
    for (float v : img.pixels) EXPECT_TRUE(std::isfinite(v));
    EXPECT_EQ(img.GetRGB(2, 3), RGB(0.f));
    EXPECT_EQ(img.GetRGB(4, 1), RGB(0.f));
    EXPECT_EQ(img.GetRGB(5, 2), RGB(1.f));  // (2 + 0) / 2: the bad sample's weight counts
    EXPECT_EQ(img.GetRGB(1, 1), RGB(1.f));

    Film clean({2, 2}, Full(2, 2), MakeBoxFilter());
    EXPECT_EQ(clean.NonFiniteCount(), 0u);
    EXPECT_FALSE(clean.FirstNonFinitePixel().has_value());
}

TEST(Film, CropWindowRestrictsImage) {
    Film film({100, 50}, {{10, 5}, {30, 25}}, MakeGaussianFilter(1.5f));
    EXPECT_EQ(film.PixelBounds(), Bounds2i({10, 5}, {30, 25}));
    // Tiles never extend beyond the crop window.
    EXPECT_EQ(film.MakeTile({{10, 5}, {30, 25}}).PixelBounds(), Bounds2i({10, 5}, {30, 25}));
    FilmTile tile = film.MakeTile({{10, 5}, {30, 25}});
    tile.AddSample({10.5f, 5.5f}, RGB(7.f));
    tile.AddSample({0.5f, 0.5f}, RGB(100.f));  // outside the crop: ignored
    film.MergeTile(tile);
    Image img = film.ToImage();
    EXPECT_EQ(img.width, 20);
    EXPECT_EQ(img.height, 20);
    EXPECT_EQ(img.GetRGB(0, 0), RGB(7.f));  // crop-relative coordinates
    EXPECT_EQ(img.GetRGB(1, 1), RGB(7.f));
    EXPECT_EQ(img.GetRGB(5, 5), RGB(0.f));

    // A crop window larger than the film is clipped.
    Film clipped({8, 8}, {{-4, 2}, {100, 6}}, MakeBoxFilter());
    EXPECT_EQ(clipped.PixelBounds(), Bounds2i({0, 2}, {8, 6}));
    EXPECT_EQ(clipped.ToImage().height, 4);
}

TEST(Film, InvalidArgumentsThrow) {
    EXPECT_THROW(Film({0, 4}, Full(0, 4), MakeBoxFilter()), std::invalid_argument);
    EXPECT_THROW(Film({4, 4}, {{2, 2}, {2, 4}}, MakeBoxFilter()), std::invalid_argument);
    EXPECT_THROW(Film({4, 4}, Full(4, 4), MakeBoxFilter(0.f)), std::invalid_argument);
    EXPECT_THROW(Film({4, 4}, Full(4, 4), MakeGaussianFilter(NAN)), std::invalid_argument);
    EXPECT_THROW(Film({4, 4}, Full(4, 4), MakeGaussianFilter(100.f)), std::invalid_argument);
    EXPECT_NO_THROW(Film({4, 4}, Full(4, 4), MakeGaussianFilter(Film::MaxFilterRadius)));
}

TEST(Film, MaxRadiusSplatsStayInBounds) {
    Film film({5, 3}, Full(5, 3), MakeTriangleFilter(Film::MaxFilterRadius));
    FilmTile tile = film.MakeTile({{2, 1}, {3, 2}});
    tile.AddSample({2.5f, 1.5f}, RGB(1.f));
    tile.AddSample({3.f, 2.f}, RGB(1.f));
    film.MergeTile(tile);
    for (float v : film.ToImage().pixels) EXPECT_EQ(v, 1.f);
}

// --stats' noise halves (FilmTile::NoiseVariance): a pixel's samples alternate between the
// halves in their order, and the variance of the mean is (mean_a - mean_b)^2 na nb / (na+nb)^2.
TEST(FilmNoise, HalvesGiveTheVarianceOfTheMean) {
    Film film({2, 1}, Full(2, 1), MakeBoxFilter());
    FilmTile tile;
    film.ResetTile(Full(2, 1), &tile, true);
    // Pixel 0: 1, 3 (halves 1 and 3): (1 - 3)^2 / 4 = 1 per channel.
    tile.AddSample({0.5f, 0.5f}, RGB(1.f));
    tile.AddSample({0.25f, 0.75f}, RGB(3.f));
    // Pixel 1: 1, 3, 5 (halves {1, 5} and {3}): equal means, 0.
    tile.AddSample({1.5f, 0.5f}, RGB(1.f));
    tile.AddSample({1.5f, 0.5f}, RGB(3.f));
    tile.AddSample({1.5f, 0.5f}, RGB(5.f));
    uint64_t pixels = 0;
    EXPECT_DOUBLE_EQ(tile.NoiseVariance(&pixels), 3.0);
    EXPECT_EQ(pixels, 2u);
    // Without the estimate the tile keeps no halves.
    film.ResetTile(Full(2, 1), &tile);
    tile.AddSample({0.5f, 0.5f}, RGB(1.f));
    tile.AddSample({0.5f, 0.5f}, RGB(3.f));
    EXPECT_EQ(tile.NoiseVariance(&pixels), 0.0);
    EXPECT_EQ(pixels, 0u);
}

// For independent samples of variance s^2 the estimate is unbiased for s^2 / n per pixel and
// channel, and a pixel with one sample has none.
TEST(FilmNoise, UnbiasedForIndependentSamples) {
    const int w = 64, h = 64, n = 8;
    TiledFilm film({w, h}, Full(w, h), MakeBoxFilter(), 16);
    film.EnableNoiseEstimate();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    std::vector<FilmTile> tiles(size_t(film.NumTiles()));
    for (int t = 0; t < film.NumTiles(); ++t) {
        film.ResetTile(t, &tiles[size_t(t)]);
        Bounds2i b = film.TilePixels(t);
        for (int y = b.pMin.y; y < b.pMax.y; ++y)
            for (int x = b.pMin.x; x < b.pMax.x; ++x)
                for (int s = 0; s < n; ++s)
                    tiles[size_t(t)].AddSample({x + u(rng), y + u(rng)},
                                               RGB(u(rng), u(rng), u(rng)));
        film.MergeNext(&tiles[size_t(t)]);
    }
    film.Finish();
    EXPECT_EQ(film.NoisePixels(), uint64_t(w * h));
    const double expected = double(w * h) * 3 * (1.0 / 12) / n;
    EXPECT_NEAR(film.NoiseVariance() / expected, 1.0, 0.05);

    TiledFilm one({4, 4}, Full(4, 4), MakeBoxFilter(), 16);
    one.EnableNoiseEstimate();
    FilmTile t1;
    one.ResetTile(0, &t1);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) t1.AddSample({x + 0.5f, y + 0.5f}, RGB(u(rng)));
    one.MergeNext(&t1);
    EXPECT_EQ(one.NoisePixels(), 0u);
}

}  // namespace
}  // namespace prism
