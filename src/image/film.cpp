// Filter evaluation, sample splatting and tile merging.
#include "image/film.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace prism {

namespace {

// Mitchell-Netravali cubic on x = |2 d / r| in [0, 2].
float Mitchell1D(float x, float B, float C) {
    x = std::abs(x);
    if (x >= 2) return 0.f;
    float x2 = x * x, x3 = x2 * x;
    if (x > 1)
        return ((-B - 6 * C) * x3 + (6 * B + 30 * C) * x2 + (-12 * B - 48 * C) * x +
                (8 * B + 24 * C)) *
               (1.f / 6.f);
    return ((12 - 9 * B - 6 * C) * x3 + (-18 + 12 * B + 6 * C) * x2 + (6 - 2 * B)) * (1.f / 6.f);
}

// sin(pi x) / (pi x), 1 at 0.
float Sinc(float x) {
    if (std::abs(x) < 1e-5f) return 1.f;  // 1 - (pi x)^2 / 6 is 1 in float there
    const float px = float(M_PI) * x;
    return std::sin(px) / px;
}

// Largest number of pixels one sample can reach along an axis: radius <= MaxFilterRadius.
constexpr int MaxSpan = 2 * int(Film::MaxFilterRadius) + 2;

bool ValidRadius(float r) { return r > 0 && r <= Film::MaxFilterRadius; }

// Keeps far-off sample positions representable as int pixel coordinates.
double ClampCoord(float v) { return std::clamp(double(v), -1e9, 1e9); }

}  // namespace

FilterKernel::FilterKernel(const Filter &f)
    : kind(f.kind), radius{f.radiusX, f.radiusY}, alpha(f.alpha), B(f.B), C(f.C), tau(f.tau) {
    for (int a = 0; a < 2; ++a) {
        invRadius[a] = 1.f / radius[a];
        expRadius[a] = std::exp(-alpha * radius[a] * radius[a]);
    }
}

float FilterKernel::Evaluate1D(int axis, float d) const {
    float r = radius[axis];
    if (!(std::abs(d) <= r)) return 0.f;
    switch (kind) {
        case Filter::Kind::Box:
            return 1.f;
        case Filter::Kind::Gaussian:
            return std::max(0.f, std::exp(-alpha * d * d) - expRadius[axis]);
        case Filter::Kind::Triangle:
            return std::max(0.f, r - std::abs(d));
        case Filter::Kind::Mitchell:
            return Mitchell1D(2.f * d * invRadius[axis], B, C);
        case Filter::Kind::LanczosSinc:
            return Sinc(d) * Sinc(d / tau);
    }
    return 0.f;
}

float Filter::Evaluate(float dx, float dy) const {
    // Not on the hot path: the film keeps a precomputed FilterKernel.
    FilterKernel k(*this);
    return k.Evaluate1D(0, dx) * k.Evaluate1D(1, dy);
}

Filter MakeBoxFilter(float radius) {
    Filter f;
    f.kind = Filter::Kind::Box;
    f.radiusX = f.radiusY = radius;
    return f;
}

Filter MakeGaussianFilter(float radius, float alpha) {
    Filter f;
    f.kind = Filter::Kind::Gaussian;
    f.radiusX = f.radiusY = radius;
    f.alpha = alpha;
    return f;
}

Filter MakeTriangleFilter(float radius) {
    Filter f;
    f.kind = Filter::Kind::Triangle;
    f.radiusX = f.radiusY = radius;
    return f;
}

Filter MakeMitchellFilter(float radius, float B, float C) {
    Filter f;
    f.kind = Filter::Kind::Mitchell;
    f.radiusX = f.radiusY = radius;
    f.B = B;
    f.C = C;
    return f;
}

Filter MakeLanczosSincFilter(float radius, float tau) {
    Filter f;
    f.kind = Filter::Kind::LanczosSinc;
    f.radiusX = f.radiusY = radius;
    f.tau = tau;
    return f;
}

void NonFiniteRecord::Add(Vec2i p) {
    ++count;
    if (!firstPixel || p.y < firstPixel->y || (p.y == firstPixel->y && p.x < firstPixel->x))
        firstPixel = p;
}

void NonFiniteRecord::Merge(const NonFiniteRecord &o) {
    uint64_t n = count + o.count;
    if (o.firstPixel) Add(*o.firstPixel);
    count = n;
}

FilmTile::FilmTile(const Bounds2i &bounds, const FilterKernel &kernel)
    : bounds_(bounds), kernel_(kernel), pixels_(size_t(bounds.Area())) {}

void FilmTile::AddSample(Vec2f pFilm, const RGB &L) {
    if (!std::isfinite(pFilm.x) || !std::isfinite(pFilm.y)) {
        // No pixel to blame and nowhere to splat: only count it.
        ++nonFinite_.count;
        return;
    }
    RGB v = L;
    if (!L.IsFinite()) {
        nonFinite_.Add(
            {int(std::floor(ClampCoord(pFilm.x))), int(std::floor(ClampCoord(pFilm.y)))});
        v = RGB(0.f);
    }
    if (noise_) AddNoiseSample(pFilm, v);
    if (kernel_.IsUnitBox()) {
        // pbrt's default box (radius 1/2): the one pixel x with x <= p < x + 1, x = floor(p),
        // with weight 1 (below, x0 == x1 == floor(p) exactly in double and |x + 1/2 - p| <= 1/2):
        // the same sums without the weight tables and their calls.
        double cx = ClampCoord(pFilm.x), cy = ClampCoord(pFilm.y);
        int x = int(cx), y = int(cy);  // |c| <= 1e9: truncation, then floor
        x -= double(x) > cx;
        y -= double(y) > cy;
        if (x < bounds_.pMin.x || x >= bounds_.pMax.x || y < bounds_.pMin.y || y >= bounds_.pMax.y)
            return;
        AddToPixel({x, y}, v);
        return;
    }
    // Pixel x receives the sample if x + 0.5 - r <= p < x + 0.5 + r, i.e. x in
    // (p - 0.5 - r, p - 0.5 + r]. Computed in double so the boundary test is exact.
    double px = ClampCoord(pFilm.x) - 0.5, py = ClampCoord(pFilm.y) - 0.5;
    double rx = kernel_.radius[0], ry = kernel_.radius[1];
    int x0 = std::max(bounds_.pMin.x, int(std::floor(px - rx)) + 1);
    int x1 = std::min(bounds_.pMax.x - 1, int(std::floor(px + rx)));
    int y0 = std::max(bounds_.pMin.y, int(std::floor(py - ry)) + 1);
    int y1 = std::min(bounds_.pMax.y - 1, int(std::floor(py + ry)));
    if (x0 > x1 || y0 > y1) return;

    // Separable filter: one weight per column and per row.
    float wx[MaxSpan], wy[MaxSpan];
    for (int x = x0; x <= x1; ++x) wx[x - x0] = kernel_.Evaluate1D(0, float(double(x) - px));
    for (int y = y0; y <= y1; ++y) wy[y - y0] = kernel_.Evaluate1D(1, float(double(y) - py));

    int stride = bounds_.Width();
    for (int y = y0; y <= y1; ++y) {
        float fy = wy[y - y0];
        if (fy == 0) continue;
        FilmPixel *row = &pixels_[size_t(y - bounds_.pMin.y) * size_t(stride)];
        for (int x = x0; x <= x1; ++x) {
            double w = double(wx[x - x0] * fy);
            if (w == 0) continue;
            FilmPixel &p = row[x - bounds_.pMin.x];
            p.r += w * v.r;
            p.g += w * v.g;
            p.b += w * v.b;
            p.weight += w;
        }
    }
}

void FilmTile::AddPixelSamples(Vec2i p, const RGB *L, int n) {
    PRISM_DCHECK(UnitBox());
    if (p.x < bounds_.pMin.x || p.x >= bounds_.pMax.x || p.y < bounds_.pMin.y ||
        p.y >= bounds_.pMax.y)
        return;
    for (int i = 0; i < n; ++i) {
        RGB v = L[i];
        if (!v.IsFinite()) {
            nonFinite_.Add(p);
            v = RGB(0.f);
        }
        AddToPixel(p, v);
    }
}

void FilmTile::AddSplat(Vec2i p, const RGB &v) {
    if (p.x < crop_.pMin.x || p.x >= crop_.pMax.x || p.y < crop_.pMin.y || p.y >= crop_.pMax.y)
        return;
    if (!v.IsFinite()) {
        nonFinite_.Add(p);
        return;
    }
    splats_.push_back({p.x, p.y, v.r, v.g, v.b});
}

void FilmTile::AddNoiseSample(Vec2f pFilm, const RGB &v) {
    double cx = ClampCoord(pFilm.x), cy = ClampCoord(pFilm.y);
    int x = int(std::floor(cx)), y = int(std::floor(cy));
    if (x < bounds_.pMin.x || x >= bounds_.pMax.x || y < bounds_.pMin.y || y >= bounds_.pMax.y)
        return;
    NoiseHalves &h =
        halves_[size_t(y - bounds_.pMin.y) * size_t(bounds_.Width()) + size_t(x - bounds_.pMin.x)];
    // Samples arrive in their order within a pixel: even ones to a, odd ones to b.
    const bool even = ((h.na + h.nb) & 1u) == 0;
    double *sum = even ? h.a : h.b;
    sum[0] += double(v.r);
    sum[1] += double(v.g);
    sum[2] += double(v.b);
    ++(even ? h.na : h.nb);
}

double FilmTile::NoiseVariance(uint64_t *pixels) const {
    double var = 0;
    uint64_t n = 0;
    for (const NoiseHalves &h : halves_) {
        if (h.na == 0 || h.nb == 0) continue;
        const double na = h.na, nb = h.nb, k = na * nb / ((na + nb) * (na + nb));
        for (int c = 0; c < 3; ++c) {
            double d = h.a[c] / na - h.b[c] / nb;
            var += d * d * k;
        }
        ++n;
    }
    if (pixels) *pixels = n;
    return var;
}

Film::Film(Vec2i fullResolution, Bounds2i cropPixels, Filter filter)
    : Film(fullResolution, cropPixels, filter, true) {}

Film::Film(Vec2i fullResolution, Bounds2i cropPixels, Filter filter, bool allocatePixels)
    : fullResolution_(fullResolution), filter_(filter) {
    if (fullResolution.x <= 0 || fullResolution.y <= 0)
        throw std::invalid_argument("film resolution must be positive");
    cropPixels_ = Intersect(cropPixels, Bounds2i({0, 0}, fullResolution));
    if (cropPixels_.Empty()) throw std::invalid_argument("film crop window covers no pixels");
    if (!ValidRadius(filter.radiusX) || !ValidRadius(filter.radiusY))
        throw std::invalid_argument("filter radius must be in (0, " +
                                    std::to_string(int(MaxFilterRadius)) + "]");
    kernel_ = FilterKernel(filter);
    if (allocatePixels) pixels_.resize(size_t(cropPixels_.Area()));
}

Bounds2i Film::TileFootprint(const Bounds2i &tilePixels) const {
    if (tilePixels.Empty()) return Bounds2i();
    // Samples lie in [pMin, pMax] (closed); invert the splat rule of AddSample.
    double rx = kernel_.radius[0], ry = kernel_.radius[1];
    Bounds2i b;
    b.pMin = {int(std::floor(tilePixels.pMin.x - 0.5 - rx)) + 1,
              int(std::floor(tilePixels.pMin.y - 0.5 - ry)) + 1};
    b.pMax = {int(std::floor(tilePixels.pMax.x - 0.5 + rx)) + 1,
              int(std::floor(tilePixels.pMax.y - 0.5 + ry)) + 1};
    b = Intersect(b, cropPixels_);
    if (b.Empty()) b = Bounds2i();
    return b;
}

FilmTile Film::MakeTile(const Bounds2i &tilePixels) const {
    return FilmTile(TileFootprint(tilePixels), kernel_);
}

void Film::ResetTile(const Bounds2i &tilePixels, FilmTile *tile, bool noise) const {
    ResetTileBounds(TileFootprint(tilePixels), tile, noise);
}

void Film::ResetTileBounds(const Bounds2i &bounds, FilmTile *tile, bool noise) const {
    tile->bounds_ = bounds;
    tile->kernel_ = kernel_;
    tile->nonFinite_ = NonFiniteRecord();
    tile->splats_.clear();
    tile->crop_ = cropPixels_;
    // assign() keeps the capacity: after the first tiles no allocation.
    tile->pixels_.assign(size_t(tile->bounds_.Area()), FilmPixel());
    tile->noise_ = noise;
    if (noise)
        tile->halves_.assign(size_t(tile->bounds_.Area()), NoiseHalves());
    else
        tile->halves_.clear();
}

void Film::MergeTile(const FilmTile &tile) {
    nonFinite_.Merge(tile.nonFinite_);
    const Bounds2i &tb = tile.bounds_;
    if (tb.Empty()) return;
    // A tile from another film (a programming error) would write out of bounds.
    PRISM_CHECK(Intersect(tb, cropPixels_) == tb);
    int tileStride = tb.Width(), filmStride = cropPixels_.Width();
    for (int y = tb.pMin.y; y < tb.pMax.y; ++y) {
        const FilmPixel *src = &tile.pixels_[size_t(y - tb.pMin.y) * size_t(tileStride)];
        FilmPixel *dst = &pixels_[size_t(y - cropPixels_.pMin.y) * size_t(filmStride) +
                                  size_t(tb.pMin.x - cropPixels_.pMin.x)];
        for (int i = 0; i < tileStride; ++i) {
            dst[i].r += src[i].r;
            dst[i].g += src[i].g;
            dst[i].b += src[i].b;
            dst[i].weight += src[i].weight;
        }
    }
}

namespace {
// One output pixel: max(0, sum(w L) / sum(w)), 0 for zero weight.
inline void ResolvePixel(const FilmPixel &p, float *out) {
    if (p.weight == 0) {
        out[0] = out[1] = out[2] = 0.f;
        return;
    }
    // std::max(0, NaN) would keep NaN; the comparison form maps it to 0.
    auto res = [](double v) { return v > 0 ? float(v) : 0.f; };
    out[0] = res(p.r / p.weight);
    out[1] = res(p.g / p.weight);
    out[2] = res(p.b / p.weight);
}
}  // namespace

Image Film::ToImage() const {
    Image img(cropPixels_.Width(), cropPixels_.Height(), 3);
    for (size_t i = 0; i < pixels_.size(); ++i) ResolvePixel(pixels_[i], &img.pixels[3 * i]);
    return img;
}

TiledFilm::TiledFilm(Vec2i fullResolution, Bounds2i cropPixels, Filter filter, int tileSize)
    : film_(fullResolution, cropPixels, filter, false), tileSize_(std::max(1, tileSize)) {
    const Bounds2i &pb = film_.cropPixels_;
    nx_ = (pb.Width() + tileSize_ - 1) / tileSize_;
    ny_ = (pb.Height() + tileSize_ - 1) / tileSize_;
    width_ = pb.Width();
    // Ring height: the most rows one tile row's footprints span (they are live together).
    for (int ty = 0; ty < ny_; ++ty) {
        Bounds2i f = film_.TileFootprint(TilePixels(ty * nx_));
        ringRows_ = std::max(ringRows_, f.Height());
    }
    finalY_ = openY_ = pb.pMin.y;
}

bool TiledFilm::ResolvesTiles() const { return inPlace_ && film_.kernel_.IsUnitBox() && !noise_; }

void TiledFilm::ResetTile(int t, FilmTile *tile) const {
    const Bounds2i tb = TilePixels(t);
    if (ResolvesTiles())
        film_.ResetTileBounds(tb, tile, false);
    else
        film_.ResetTile(tb, tile, noise_);
}

void TiledFilm::ResolveTile(int t, const FilmTile &tile) {
    PRISM_CHECK(ResolvesTiles() && next_ == 0 && tile.bounds_ == TilePixels(t) &&
                tile.splats_.empty());
    {
        std::lock_guard<std::mutex> lock(resolveMutex_);
        if (image_.pixels.empty()) {
            // The first tile allocates the frame, uninitialized: each tile writes its own pixels
            // (and touches its own pages) below.
            const Bounds2i &pb = film_.cropPixels_;
            image_ = Image::Uninitialized(pb.Width(), pb.Height(), 3);
            resolved_.assign(size_t(NumTiles()), 0);
        }
        nonFinite_.Merge(tile.nonFinite_);
    }
    const Bounds2i &tb = tile.bounds_;
    const int w = tb.Width();
    for (int y = tb.pMin.y; y < tb.pMax.y; ++y) {
        const FilmPixel *src = &tile.pixels_[size_t(y - tb.pMin.y) * size_t(w)];
        float *out = ImagePixel(tb.pMin.x, y);
        // The ring's sum of this pixel would be 0 + the tile's sum: the same double.
        for (int x = 0; x < w; ++x) ResolvePixel(src[x], out + 3 * size_t(x));
    }
    resolved_[size_t(t)] = 1;
}

Bounds2i TiledFilm::TilePixels(int t) const {
    const Bounds2i &pb = film_.cropPixels_;
    int tx = t % nx_, ty = t / nx_;
    Bounds2i tb;
    tb.pMin = {pb.pMin.x + tx * tileSize_, pb.pMin.y + ty * tileSize_};
    tb.pMax = {std::min(tb.pMin.x + tileSize_, pb.pMax.x),
               std::min(tb.pMin.y + tileSize_, pb.pMax.y)};
    return tb;
}

void TiledFilm::FinalizeRowsBelow(int y) {
    for (; finalY_ < y; ++finalY_) {
        const FilmPixel *row = Row(finalY_);
        float *out = ImagePixel(film_.cropPixels_.pMin.x, finalY_);
        // Rows no tile reached (only possible when cancelled) were never opened: zero.
        if (finalY_ >= openY_) {
            std::fill(out, out + size_t(width_) * 3, 0.f);
            continue;
        }
        for (int x = 0; x < width_; ++x) ResolvePixel(row[x], out + 3 * size_t(x));
    }
    openY_ = std::max(openY_, finalY_);
}

void TiledFilm::OpenRowsBelow(int y) {
    for (; openY_ < y; ++openY_) {
        FilmPixel *row = Row(openY_);
        std::fill(row, row + width_, FilmPixel());
    }
}

void TiledFilm::MergeNext(const FilmTile *tile) {
    PRISM_CHECK(next_ < NumTiles() && resolved_.empty());
    if (ring_.empty()) {
        // The first merge allocates the ring and the zero-filled frame (rows no tile reaches,
        // when cancelled, stay zero).
        ring_.resize(size_t(ringRows_) * size_t(width_));
        image_ = Image(film_.cropPixels_.Width(), film_.cropPixels_.Height(), 3);
    }
    int t = next_++;
    // Rows above this tile row's footprint are complete: no later tile reaches them.
    Bounds2i f = film_.TileFootprint(TilePixels(t - t % nx_));
    FinalizeRowsBelow(f.pMin.y);
    OpenRowsBelow(f.pMax.y);
    if (!tile) return;
    nonFinite_.Merge(tile->nonFinite_);
    if (!tile->splats_.empty()) {
        const Bounds2i &crop = film_.cropPixels_;
        if (splat_.empty()) splat_.assign(size_t(crop.Area()) * 3, 0.0);
        for (const FilmSplat &sp : tile->splats_) {
            PRISM_CHECK(sp.x >= crop.pMin.x && sp.x < crop.pMax.x && sp.y >= crop.pMin.y &&
                        sp.y < crop.pMax.y);
            double *d =
                &splat_[(size_t(sp.y - crop.pMin.y) * size_t(width_) + size_t(sp.x - crop.pMin.x)) *
                        3];
            d[0] += double(sp.r), d[1] += double(sp.g), d[2] += double(sp.b);
        }
    }
    if (noise_) {
        uint64_t n = 0;
        noiseVariance_ += tile->NoiseVariance(&n);
        noisePixels_ += n;
    }
    const Bounds2i &tb = tile->bounds_;
    if (tb.Empty()) return;
    const Bounds2i &pb = film_.cropPixels_;
    PRISM_CHECK(tb.pMin.y >= finalY_ && tb.pMax.y <= openY_ && tb.pMin.x >= pb.pMin.x &&
                tb.pMax.x <= pb.pMax.x);
    int tileStride = tb.Width();
    for (int y = tb.pMin.y; y < tb.pMax.y; ++y) {
        const FilmPixel *src = &tile->pixels_[size_t(y - tb.pMin.y) * size_t(tileStride)];
        FilmPixel *dst = Row(y) + (tb.pMin.x - pb.pMin.x);
        for (int i = 0; i < tileStride; ++i) {
            dst[i].r += src[i].r;
            dst[i].g += src[i].g;
            dst[i].b += src[i].b;
            dst[i].weight += src[i].weight;
        }
    }
}

Image TiledFilm::Finish() {
    if (!resolved_.empty()) {
        // Tiles resolved in place: zero those not rendered (cancelled).
        for (int t = 0; t < NumTiles(); ++t) {
            if (resolved_[size_t(t)]) continue;
            const Bounds2i tb = TilePixels(t);
            for (int y = tb.pMin.y; y < tb.pMax.y; ++y) {
                float *out = ImagePixel(tb.pMin.x, y);
                std::fill(out, out + 3 * size_t(tb.Width()), 0.f);
            }
        }
        return std::move(image_);
    }
    while (next_ < NumTiles()) MergeNext(nullptr);
    FinalizeRowsBelow(film_.cropPixels_.pMax.y);
    // The splats, unfiltered, over the filtered samples (pbrt-v3 Film::WriteImage).
    for (size_t i = 0; i < splat_.size(); ++i)
        image_.pixels[i] = float(double(image_.pixels[i]) + splat_[i]);
    return std::move(image_);
}

}  // namespace prism
