// Camera, Film, Sampler, PixelFilter and Integrator directives → the RenderScene's camera,
// resolution and crop, sample count, reconstruction filter and maximum depth (with
// BuildSettings' replacements applied). Run in this order: the camera needs the resolution,
// and every later step needs the camera's renderFromWorld.
#pragma once

#include "assembly/build_context.h"

namespace prism {

void BuildFilm(BuildContext &ctx);     // resolution, crop window, scale, filename
void BuildCamera(BuildContext &ctx);   // camera and renderFromWorld
void BuildSampler(BuildContext &ctx);  // samples per pixel
void BuildPixelFilter(BuildContext &ctx);
// Charges the film's memory (EstimateFilmBytes: film, tiles with the filter's margins, image
// and its encoded copy) to the budget; after BuildFilm and BuildPixelFilter.
void ChargeFilmMemory(BuildContext &ctx);
void BuildIntegratorSettings(BuildContext &ctx);  // the integrator, why, and maxdepth

}  // namespace prism
