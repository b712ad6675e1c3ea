// Pixel reconstruction: samples are splatted through a pixel filter into per-tile accumulators
// (FilmTile) that are merged into the Film in a fixed order, so results do not depend on how
// many threads rendered the tiles.
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "core/color.h"
#include "core/vecmath.h"
#include "image/bounds2.h"
#include "image/image.h"

namespace prism {

// pbrt's pixel filters. All are separable: Evaluate(dx, dy) = f(dx) * f(dy), where dx, dy are
// offsets from the pixel centre. Radii must be in (0, Film::MaxFilterRadius].
struct Filter {
    enum class Kind { Box, Gaussian, Triangle, Mitchell, LanczosSinc };
    Kind kind = Kind::Box;
    float radiusX = 0.5f, radiusY = 0.5f;
    float alpha = 2.f;               // gaussian falloff
    float B = 1.f / 3, C = 1.f / 3;  // mitchell-netravali parameters
    float tau = 3.f;                 // lanczos sinc: the window's period, in sinc's lobes

    // Zero outside the radius (the box is 1 on the closed [-r, r]^2).
    float Evaluate(float dx, float dy) const;
};

Filter MakeBoxFilter(float radius = 0.5f);
Filter MakeGaussianFilter(float radius = 2.f, float alpha = 2.f);
Filter MakeTriangleFilter(float radius = 2.f);
Filter MakeMitchellFilter(float radius = 2.f, float B = 1.f / 3, float C = 1.f / 3);
// pbrt's "sinc": sinc(d) sinc(d / tau) within the radius (a Lanczos window).
Filter MakeLanczosSincFilter(float radius = 4.f, float tau = 3.f);

// A Filter with its per-axis constants precomputed, evaluated one axis at a time.
struct FilterKernel {
    Filter::Kind kind = Filter::Kind::Box;
    float radius[2] = {0.5f, 0.5f};
    float invRadius[2] = {2.f, 2.f};
    float expRadius[2] = {0, 0};  // gaussian: exp(-alpha r^2)
    float alpha = 2.f, B = 1.f / 3, C = 1.f / 3, tau = 3.f;

    FilterKernel() = default;
    explicit FilterKernel(const Filter &f);
    // Zero for |d| > radius[axis].
    float Evaluate1D(int axis, float d) const;
    // pbrt's default box (radius 1/2): a sample goes to the one pixel containing it, weight 1.
    bool IsUnitBox() const {
        return kind == Filter::Kind::Box && radius[0] == 0.5f && radius[1] == 0.5f;
    }
};

// Sums of filter-weighted radiance in double precision: with many samples per pixel this keeps
// the result independent of the summation order to far below float resolution.
struct FilmPixel {
    double r = 0, g = 0, b = 0, weight = 0;
};

// A pixel's samples split in two halves by their order (even and odd), each with its own
// unfiltered sum: the noise estimate of --stats (FilmTile::NoiseVariance).
struct NoiseHalves {
    double a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
    uint32_t na = 0, nb = 0;
};

// Radiance added to one pixel unfiltered, beside the filtered samples (light tracing: pbrt-v3
// Film::AddSplat); the caller has already divided it by the samples per pixel.
struct FilmSplat {
    int32_t x = 0, y = 0;  // the pixel, in full-image coordinates
    float r = 0, g = 0, b = 0;
};

// Record of samples with NaN/Inf radiance; the reported pixel is the smallest in (y, x) order
// so that it does not depend on the order in which tiles finish.
struct NonFiniteRecord {
    uint64_t count = 0;
    std::optional<Vec2i> firstPixel;
    void Add(Vec2i p);
    void Merge(const NonFiniteRecord &o);
};

// Accumulator for the samples of one tile; created by Film::MakeTile. Not thread-safe: one
// thread fills one tile. Movable, so tiles can be stored and merged later.
class FilmTile {
  public:
    FilmTile() = default;

    // pFilm is the continuous raster position: pixel (x, y) covers [x, x+1) x [y, y+1) and has
    // its centre at (x + 0.5, y + 0.5). The sample goes to every pixel of this tile's bounds
    // whose centre c satisfies c - r <= pFilm < c + r on both axes (half-open, so with the
    // default box filter a sample lands in exactly the one pixel containing it). Radiance with
    // a NaN/Inf component is counted and added as 0; its filter weight still counts.
    void AddSample(Vec2f pFilm, const RGB &L);
    // pbrt's default box filter (radius 1/2) without the noise estimate: samples then go to
    // the one pixel that contains them with weight 1.
    bool UnitBox() const { return kernel_.IsUnitBox() && !noise_; }
    // With UnitBox(): adds n samples that all lie in pixel p (render/sampler.h FilmPosition
    // keeps them there), in order: the same sums as AddSample of each, without locating each.
    void AddPixelSamples(Vec2i p, const RGB *L, int n);
    // A splat onto pixel p of the crop window, which may lie outside this tile: kept in order
    // and summed into the image when the tile is merged (TiledFilm::MergeNext). A splat with
    // a NaN/Inf component is counted (at p) and dropped; one outside the crop is dropped.
    void AddSplat(Vec2i p, const RGB &v);
    // The splats in the order they were added (prism-mpi ships them with the sums).
    std::vector<FilmSplat> &Splats() { return splats_; }
    const std::vector<FilmSplat> &Splats() const { return splats_; }

    // Pixels this tile accumulates into (within the film's crop window).
    const Bounds2i &PixelBounds() const { return bounds_; }
    const NonFiniteRecord &NonFinite() const { return nonFinite_; }
    // The sums, row-major over PixelBounds(), and the NaN/Inf record, for a tile rendered in
    // another process (prism-mpi): filled into a tile the receiver reset for the same pixels.
    std::span<FilmPixel> Sums() { return pixels_; }
    std::span<const FilmPixel> Sums() const { return pixels_; }
    void SetNonFinite(const NonFiniteRecord &r) { nonFinite_ = r; }

    // With the noise estimate on (Film::ResetTile): the estimated variance of the box-filtered
    // mean of each pixel that has samples in both halves, summed over those pixels and the
    // three channels: sum (mean_a - mean_b)^2 na nb / (na + nb)^2, which is unbiased for
    // independent samples and errs high for stratified ones (the halves are anti-correlated).
    // Samples count for the pixel that contains them (their home pixel).
    double NoiseVariance(uint64_t *pixels = nullptr) const;

  private:
    void AddNoiseSample(Vec2f pFilm, const RGB &v);
    // The unit box's sum for pixel p of bounds_: v (finite) with weight 1.
    void AddToPixel(Vec2i p, const RGB &v) {
        FilmPixel &px = pixels_[size_t(p.y - bounds_.pMin.y) * size_t(bounds_.Width()) +
                                size_t(p.x - bounds_.pMin.x)];
        px.r += double(v.r);
        px.g += double(v.g);
        px.b += double(v.b);
        px.weight += 1.0;
    }

    friend class Film;
    friend class TiledFilm;
    FilmTile(const Bounds2i &bounds, const FilterKernel &kernel);

    Bounds2i bounds_;
    FilterKernel kernel_;
    std::vector<FilmPixel> pixels_;
    NonFiniteRecord nonFinite_;
    bool noise_ = false;
    std::vector<NoiseHalves> halves_;  // over bounds_, when noise_
    std::vector<FilmSplat> splats_;
    Bounds2i crop_;  // the film's crop window (where splats may land)
};

class Film {
  public:
    static constexpr float MaxFilterRadius = 32.f;

    // cropPixels is clipped to the full resolution. Throws std::invalid_argument for a
    // non-positive resolution, an empty crop window or a filter radius outside
    // (0, MaxFilterRadius]; callers validate user input first and report it with a location.
    Film(Vec2i fullResolution, Bounds2i cropPixels, Filter filter);

    Vec2i FullResolution() const { return fullResolution_; }
    const Bounds2i &PixelBounds() const { return cropPixels_; }  // the crop window
    const Filter &GetFilter() const { return filter_; }

    // A tile covering every crop pixel that samples with pFilm in [pMin, pMax] (closed, so a
    // sample rounded up onto the far edge still fits) of tilePixels can reach.
    FilmTile MakeTile(const Bounds2i &tilePixels) const;
    // The same tile in `tile`, reusing its buffer (no allocation once it is large enough);
    // noise: the tile also keeps the noise halves (FilmTile::NoiseVariance).
    void ResetTile(const Bounds2i &tilePixels, FilmTile *tile, bool noise = false) const;
    // The crop pixels MakeTile(tilePixels) accumulates into.
    Bounds2i TileFootprint(const Bounds2i &tilePixels) const;

    // Adds the tile's weighted sums. Not thread-safe; merge tiles in a fixed order for
    // reproducible output.
    void MergeTile(const FilmTile &tile);

    // Crop-sized RGB image (pixel (0, 0) is the crop window's top-left corner) holding
    // max(0, sum(w L) / sum(w)); pixels with zero total weight are 0. The clamp follows pbrt-v3
    // and only matters for filters with negative lobes (mitchell).
    Image ToImage() const;

    uint64_t NonFiniteCount() const { return nonFinite_.count; }
    std::optional<Vec2i> FirstNonFinitePixel() const { return nonFinite_.firstPixel; }

  private:
    friend class TiledFilm;
    Film(Vec2i fullResolution, Bounds2i cropPixels, Filter filter, bool allocatePixels);
    // ResetTile with the tile's pixel bounds given (TiledFilm's tiles resolved in place).
    void ResetTileBounds(const Bounds2i &bounds, FilmTile *tile, bool noise) const;

    Vec2i fullResolution_;
    Bounds2i cropPixels_;
    Filter filter_;
    FilterKernel kernel_;
    std::vector<FilmPixel> pixels_;
    NonFiniteRecord nonFinite_;
};

// A film for a regular grid of square tiles merged in row-major order (tile 0, 1, 2, ...): the
// image is written band by band as tile rows complete, and only the rows that tiles still to
// come can reach are kept as double sums (a ring of about tileSize + 2 radius rows), so no
// full-frame accumulator is allocated or zeroed. The result is bit-identical to a Film that
// merges the same tiles in the same order.
class TiledFilm {
  public:
    TiledFilm(Vec2i fullResolution, Bounds2i cropPixels, Filter filter, int tileSize);

    int NumTiles() const { return nx_ * ny_; }
    Bounds2i TilePixels(int t) const;
    // Reuses `tile`'s buffer for tile t (its own pixels only, with ResolvesTiles()).
    void ResetTile(int t, FilmTile *tile) const;
    // Tiles keep the noise halves, and merged tiles add their NoiseVariance.
    void EnableNoiseEstimate() { noise_ = true; }

    // Tiles resolved in place, for pbrt's default box filter (radius 1/2) without the noise
    // estimate: a tile then holds just its own pixels, and ResolveTile writes them to the image
    // from the thread that rendered it, with no ring, no in-order merge and no zero-filled
    // frame up front. The caller promises that every sample it adds to a tile lies in the
    // pixel it was drawn for (the render's samples do: render/sampler.h FilmPosition); a
    // sample outside the tile would be lost, where the merged tiles' one-pixel border keeps
    // it. Each pixel is resolved from the same double sums as through MergeNext, so for such
    // samples the image is the same, bit for bit. Returns ResolvesTiles(); call it before
    // the first ResetTile and after EnableNoiseEstimate.
    bool EnableResolveInPlace() {
        inPlace_ = true;
        return ResolvesTiles();
    }
    bool ResolvesTiles() const;
    // Writes tile t's pixels to the image. Thread-safe for distinct tiles; only with
    // ResolvesTiles(), and not mixed with MergeNext.
    void ResolveTile(int t, const FilmTile &tile);
    double NoiseVariance() const { return noiseVariance_; }
    uint64_t NoisePixels() const { return noisePixels_; }

    // Merges the next tile in order; nullptr for a tile that was not rendered (cancelled).
    void MergeNext(const FilmTile *tile);
    int NextTile() const { return next_; }
    // Merges nothing for the remaining tiles and returns the crop-sized image (Film::ToImage).
    Image Finish();

    uint64_t NonFiniteCount() const { return nonFinite_.count; }
    std::optional<Vec2i> FirstNonFinitePixel() const { return nonFinite_.firstPixel; }

  private:
    FilmPixel *Row(int y) { return &ring_[size_t(y % ringRows_) * size_t(width_)]; }
    // The image's pixel (x, y) in crop coordinates: its 3 floats.
    float *ImagePixel(int x, int y) {
        const Bounds2i &pb = film_.cropPixels_;
        return &image_.pixels[(size_t(y - pb.pMin.y) * size_t(width_) + size_t(x - pb.pMin.x)) * 3];
    }
    void FinalizeRowsBelow(int y);  // writes image rows [finalY_, y) and frees their ring rows
    void OpenRowsBelow(int y);      // zeroes ring rows [openY_, y)

    Film film_;  // crop, filter and footprints; its own pixel buffer stays empty
    int tileSize_, nx_ = 0, ny_ = 0;
    int width_ = 0, ringRows_ = 1;
    std::vector<FilmPixel> ring_;
    // The merged tiles' splats, 3 doubles per crop pixel (allocated at the first splat) and
    // added to the image by Finish: splats reach any pixel, also rows already finalized.
    std::vector<double> splat_;
    int next_ = 0;
    int finalY_ = 0, openY_ = 0;  // crop rows: [finalY_, openY_) are live in the ring
    Image image_;
    NonFiniteRecord nonFinite_;
    // ResolveTile: which tiles were written (the rest are zeroed by Finish), and a lock for
    // nonFinite_.
    std::vector<uint8_t> resolved_;
    std::mutex resolveMutex_;
    bool noise_ = false, inPlace_ = false;
    double noiseVariance_ = 0;
    uint64_t noisePixels_ = 0;
};

}  // namespace prism
