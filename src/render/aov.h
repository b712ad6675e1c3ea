// Arbitrary output variables (AOVs): per-pixel layers beside the beauty image, written into one
// multi-channel EXR (`prism render --aov`, Film "string aovs"; docs/USAGE.md "AOVs"). They are
// computed from the render itself, tile by tile, by the one tile driver (render/renderer.h), under
// every integrator: the variance and the direct/indirect split from the beauty's own samples, the
// geometric layers from the first hit of the same camera rays (as Mitsuba's aov integrator). A
// render without AOVs runs none of this code and its image is unchanged.
//
// Filtering: the geometric layers (depth, P, N, Ng, uv) and the ids come from one sample per
// pixel, the one nearest the pixel centre (the centre itself at 1 spp), so ids are never blended
// at edges. albedo is the mean over the pixel's samples (a box over the pixel). direct and
// indirect are splatted through the Film's pixel filter like the beauty, so
// direct + indirect = RGB (to float rounding). variance is the unbiased sample variance of the
// pixel's own samples (0 at 1 spp).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/transform.h"
#include "geometry/interaction.h"
#include "image/bounds2.h"

namespace prism {

struct RenderScene;

enum class Aov {
    Depth,        // Z: view-space distance along the camera axis (+inf where nothing is hit)
    Position,     // P.X P.Y P.Z: world-space hit point
    Normal,       // N.X N.Y N.Z: shading normal (world space)
    GeoNormal,    // Ng.X Ng.Y Ng.Z: geometric normal, turned toward the ray
    Albedo,       // albedo.R albedo.G albedo.B: diffuse reflectance of the first hit
    UV,           // uv.U uv.V
    ShapeId,      // shape_id: declaration number (1-based; 0: no hit)
    PrimitiveId,  // primitive_id: triangle index (0 for analytic shapes; -1: no hit)
    InstanceId,   // instance_id: 1 + ObjectInstance index (0: not in an instance)
    MaterialId,   // material_id: 1 the default matte, 2 + Material declaration index
    Direct,       // direct.R/G/B: emission + direct lighting at the first hit
    Indirect,     // indirect.R/G/B: everything else (specular reflection and refraction)
    Variance,     // variance.R/G/B: per-pixel sample variance of the beauty
    Count
};

const char *AovName(Aov a);  // "depth", "P", "N", "Ng", "albedo", "uv", "shape_id", ...
// The EXR channel names of one AOV ("Z"; "P.X", "P.Y", "P.Z"; ...).
std::vector<std::string> AovChannels(Aov a);
// "all" or a comma-separated list of AovName()s (case-sensitive; duplicates are merged, the
// order is Aov's). Returns false with a message naming the bad entry.
bool ParseAovList(const std::string &list, std::vector<Aov> *aovs, std::string *error);

// The ids of the declaration a hit belongs to (shape, material, instance); app/shape_lookup.h.
using AovIdFn =
    std::function<void(const SurfaceInteraction &si, int *shape, int *material, int *instance)>;

// One AOV's pixels over the render's pixel bounds, channels interleaved, top row first.
struct AovLayer {
    Aov aov;
    std::vector<std::string> channels;
    std::vector<float> pixels;
};

struct TileContext;
struct TileSamples;
class Film;
class FilmTile;

// The AOVs of one render (or of every pass of a progressive render), filled tile by tile by
// the tile driver. Tiles write disjoint pixels, so AddTile runs on any thread; the direct and
// indirect films merge their tiles in index order at EndPass, so the layers do not depend on
// the thread count.
class AovFrame {
  public:
    AovFrame(const RenderScene &scene, const std::vector<Aov> &aovs, AovIdFn ids);
    ~AovFrame();
    AovFrame(const AovFrame &) = delete;
    AovFrame &operator=(const AovFrame &) = delete;

    // The integrator must give each sample's direct part (TileSamples::wantDirect).
    bool WantsDirect() const { return split_; }
    // Before a pass of nTiles tiles.
    void BeginPass(int nTiles);
    // Tile t of the pass: `samples` as the film takes them (film scale and clamp applied).
    void AddTile(const TileContext &ctx, int t, const TileSamples &samples);
    // After the pass's last tile: its samples per pixel weigh it against the other passes.
    void EndPass(int spp);
    std::vector<AovLayer> Layers() const;

  private:
    void AddGeometry(const TileContext &ctx, const Bounds2i &tb);
    float &At(Aov a, int x, int y, size_t c);

    const RenderScene &scene_;
    std::vector<Aov> aovs_;
    AovIdFn ids_;
    Bounds2i pb_;
    int slot_[size_t(Aov::Count)];
    std::vector<AovLayer> layers_;
    bool split_ = false, variance_ = false, geometric_ = false, albedo_ = false;
    bool firstPass_ = true;
    // The variance: per pixel and channel the running mean and sum of squared deviations of
    // every pass's samples (Chan et al.'s pairwise update), and their count.
    std::vector<double> mean_, m2_;
    uint64_t samples_ = 0;
    // Direct and indirect: this pass's films and tiles; the passes' images summed by spp.
    std::unique_ptr<Film> directFilm_, indirectFilm_;
    std::vector<FilmTile> directTiles_, indirectTiles_;
    std::vector<double> directSum_, indirectSum_;
    int splitSpp_ = 0;
};

// Whether the AOVs need an integrator whose direct part is exact (IntegratorTraits::directAov).
bool AovsNeedDirect(const std::vector<Aov> &aovs);

}  // namespace prism
