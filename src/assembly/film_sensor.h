// pbrt-v4's film sensor (Film "rgb", "gbuffer", "spectral"): the imaging ratio of its ISO and
// the camera's shutter time, and white balance, as one linear map of the rendered sRGB.
#pragma once

#include <array>

#include "assembly/build_context.h"

namespace prism {

// The chromaticity (x, y) of CIE daylight of correlated colour temperature T kelvin: the CIE
// daylight locus polynomials (as pbrt-v4 evaluates them, at T x 1.4388 / 1.4380, the CCT of
// the current radiation constant, so that 6500 K is D65).
std::array<double, 2> DaylightChromaticity(double T);

// The linear-sRGB matrix (row-major) of a Bradford chromatic adaptation that maps the white
// of chromaticity `from` onto sRGB's own (D65).
std::array<float, 9> WhiteBalanceMatrix(std::array<double, 2> from);

// Reads a pbrt-v4 Film's "iso", "whitebalance", "sensor" and "savefp16" into scene.filmScale
// and scene.filmColor (pbrt-v4's imaging ratio: shutter time x iso / 100). A pbrt-v3 Film
// ("image") reads none of them.
void BuildFilmSensor(BuildContext &ctx);

}  // namespace prism
