// pbrt-v3's "sppm" integrator: stochastic progressive photon mapping (Hachisuka and Jensen
// 2009). Each iteration a camera pass finds one visible point per pixel (the first non-specular
// surface after specular chains, with direct lighting there), a hash grid is built over the
// visible points, a photon pass traces photons from the lights (chosen by power) and deposits
// them into the visible points within each pixel's radius through their BSDF, and every
// pixel's radius, flux and photon count are updated (alpha 2/3). It is a whole-frame
// integrator (Integrator::RendersWholeFrame): the passes share the frame's visible points.
// Deterministic for any thread count: photon i of iteration k draws from a stream that is a
// pure function of (k, i), and deposits are summed per visible point chunk by chunk in chunk
// order. docs/INTEGRATORS.md.
#pragma once

#include <cstdint>
#include <vector>

#include "render/bsdf.h"
#include "render/integrator.h"
#include "render/light_sampling.h"

namespace prism {

class FrameContext;

struct SppmParams {
    int iterations = 64;               // "numiterations"
    int64_t photonsPerIteration = -1;  // "photonsperiteration" (-1: the pixel count)
    float radius = 1;                  // "radius": the initial search radius, in world units
    int writeFrequency = 1 << 30;      // "imagewritefrequency": an image every this many iterations
};

// A visible point's BSDF, reduced to what photon deposits evaluate: the shading frame and the
// parts with non-delta lobes (their lobes in SppmPass::lobes).
struct SppmVisiblePoint {
    Vec3f p, wo;
    Vec3f ss, ts, ns, ng;
    RGB beta;  // the camera path's throughput; black: the pixel has no visible point
    uint32_t firstPart = 0, numParts = 0;
};

// One non-delta part of a visible point's BSDF.
struct SppmPart {
    RGB weight;
    BxDFLobes lobes;
};

// A pixel's state across iterations.
struct SppmPixel {
    RGB Ld;          // direct lighting, summed over iterations
    float radius;    // the current search radius
    RGB tau;         // the flux, scaled to the current radius
    float N = 0;     // the photon count (a real number: alpha scales it)
    RGB phi;         // this iteration's deposits
    uint32_t M = 0;  // and how many
};

// One iteration's visible points, in crop-window pixel order, and their BSDF parts per tile
// of the frame (each tile's camera pass appends its own).
struct SppmPass {
    std::vector<SppmVisiblePoint> points;
    std::vector<std::vector<SppmPart>> lobes;  // by tile
    std::vector<uint32_t> tileOfPoint;         // the tile whose lobes a point's parts are in

    const SppmPart &Part(uint32_t point, uint32_t k) const {
        return lobes[tileOfPoint[point]][points[point].firstPart + k];
    }
    // f(wo, wi) of visible point i's non-delta lobes, as BSDF::f evaluates it.
    RGB f(uint32_t i, const Vec3f &wi) const;
};

// The visible points of one iteration in a uniform grid hashed into buckets (pbrt-v3's grid of
// linked lists as an array: each bucket's points in point order, so lookups are deterministic).
// A point is in every cell its radius sphere's bounds overlap, once per bucket.
class SppmGrid {
  public:
    // Builds the grid over the points with a non-black beta, pixel i's radius radii[i].
    void Build(const std::vector<SppmVisiblePoint> &points, const std::vector<SppmPixel> &pixels);
    // The points whose cells hash to p's bucket (a superset of those within their radius of p);
    // empty outside the grid.
    std::pair<const uint32_t *, const uint32_t *> Candidates(const Vec3f &p) const;
    uint64_t Bytes() const;

  private:
    bool Cell(const Vec3f &p, int c[3]) const;
    uint32_t Bucket(int x, int y, int z) const;
    Vec3f lo_, hi_;
    int res_[3] = {1, 1, 1};
    std::vector<uint32_t> start_, entries_;
};

class SppmIntegrator : public Integrator {
  public:
    explicit SppmIntegrator(const SppmParams &params) : params_(params) {}
    const char *Name() const override { return "sppm"; }
    IntegratorTraits Traits() const override;
    void Prepare(const RenderScene &scene) override;
    // Not a per-sample integrator: Render() calls RenderFrame. Li gives nothing.
    RGB Li(const RenderScene &, const Ray &, const PixelSamples &, RayCounters &,
           RGB *direct) const override;
    bool RendersWholeFrame() const override { return true; }
    Image RenderFrame(const FrameContext &frame) const override;

    const SppmParams &Settings() const { return params_; }

  private:
    // The camera pass of iteration `iter` (sppm_camera.cpp).
    void CameraPass(const FrameContext &frame, int iter, SppmPass &pass,
                    std::vector<SppmPixel> &pixels) const;
    // The photon pass (sppm_photons.cpp): deposits into pixels[i].phi and M.
    void PhotonPass(const FrameContext &frame, int iter, int64_t photons, const SppmPass &pass,
                    const SppmGrid &grid, std::vector<SppmPixel> &pixels) const;
    Image MakeImage(const FrameContext &frame, const std::vector<SppmPixel> &pixels, int done,
                    int64_t photons) const;

    SppmParams params_;
    LightChooser uniform_, power_;  // direct lighting (pbrt-v3: uniform); photons by power
};

// Photons are traced in chunks of this many; each chunk sums its deposits per visible point
// on its own and the chunks are merged in order, so the sums do not depend on the threads.
inline constexpr int64_t SppmPhotonChunk = 1024;
// The chunks traced in parallel before their deposits are merged (bounds the deposit lists).
inline constexpr int SppmChunksInFlight = 16;

}  // namespace prism
