// Measured scattering coefficients by name: a medium's "preset" and a subsurface material's
// "name" (pbrt-v3 GetMediumScatteringProperties).
#pragma once

#include <string>

#include "core/color.h"

namespace prism {

// pbrt-v3's default coefficients of a homogeneous medium and of Material "subsurface" (whole
// milk, mm^-1).
inline constexpr RGB WholeMilkSigmaA(.0011f, .0024f, .014f), WholeMilkSigmaS(2.55f, 3.21f, 3.77f);

// The measured σa and reduced σ's (mm^-1) of the medium `name`; false when there is none.
bool MeasuredMedium(const std::string &name, RGB *sigmaA, RGB *sigmaPrimeS);

}  // namespace prism
