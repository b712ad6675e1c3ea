// Progressive rendering for `--time-limit`: the image is rendered in passes, each a complete
// render with sample patterns of its own (SamplerSettings::seed), and the passes are averaged
// weighted by their samples per pixel. Passes grow (2, 2, 4, 8, ... samples per pixel, sized
// from the measured time per sample to fit the time left) until the time runs out or the
// sample budget is spent. A pass that has started finishes, so the image is always complete.
#pragma once

#include "render/renderer.h"

namespace prism {

// The budget of a time limit without --spp (the largest --spp).
inline constexpr int MaxProgressiveSpp = 1 << 16;

struct TimeLimit {
    double seconds = 0;  // time left for rendering, counted from the call
    int maxSpp = 1;      // the sample budget: at most this many samples per pixel in all
};

// The pass sizes so far decide the next: the largest count that fits the time left at the
// measured seconds per sample per pixel (with a 10% margin), at most the samples done so far
// (at least 2: passes double the total) and the budget left; 0 when no pass fits. Samples
// per pixel counts below 2 are not started unless they finish the budget (a pass of 1 has
// no noise estimate of its own).
int NextPassSpp(int done, int maxSpp, double secondsLeft, double secondsPerSpp);

// Renders `scene` within `limit`, each pass with the scene's sampler at the pass's spp and
// seed. stats->spp is the total samples per pixel and stats->passSpp lists the passes; the
// noise variance (with scene.estimateNoise) is that of the averaged image. `aovs`, when given,
// collects every pass's tiles.
Image RenderProgressive(const RenderScene &scene, const TimeLimit &limit, RenderStats *stats,
                        const ProgressFn &progress = {}, const volatile int *cancel = nullptr,
                        AovFrame *aovs = nullptr);

}  // namespace prism
