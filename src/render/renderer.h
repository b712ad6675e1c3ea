// The tile-parallel render loop: TBB over tiles, each tile filtered into its own buffer, tiles
// merged in a fixed order so the image is identical for any thread count.
#pragma once

#include <functional>

#include "image/image.h"
#include "render/render_scene.h"
#include "render/whitted.h"

namespace prism {

// Tiles are squares of this many pixels (the last row and column may be smaller); the memory
// estimate of the film (core/memory.h EstimateFilmBytes) and bench's ceiling pass use it.
inline constexpr int RenderTileSize = 16;
// Camera rays are traced in packets of RenderPacketW x RenderPacketH pixels at one sample
// index (bench's ceiling pass traces the same packets).
inline constexpr int RenderPacketW = 4, RenderPacketH = 4;

struct RenderStats {
    double renderSeconds = 0;
    RayCounters rays;
    uint64_t nonFiniteSamples = 0;
    std::optional<Vec2i> firstNonFinitePixel;
    bool cancelled = false;   // the cancel flag was raised: the image is incomplete
    uint32_t kernelMask = 0;  // the kernel that ran (render/kernel.h KernelMaskName)
};

// Called with the fraction done (0..1), from a single thread.
using ProgressFn = std::function<void(double fraction)>;

// `cancel`, when given, is polled between tiles; once it reads true the remaining tiles are
// skipped and stats->cancelled is set.
Image Render(const RenderScene &scene, RenderStats *stats, const ProgressFn &progress = {},
             const volatile int *cancel = nullptr);

}  // namespace prism
