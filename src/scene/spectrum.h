// Conversion of pbrt's spectral parameter types (xyz, blackbody, sampled spectra and .spd
// spectrum files) to the linear sRGB (Rec.709 primaries, D65 white) values the renderer
// works in.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/color.h"
#include "core/error.h"

namespace prism {

class MemoryBudget;

// CIE 1931 2° colour matching functions, from the multi-lobe Gaussian fit of Wyman, Sloan and
// Shirley 2013 ("Simple Analytic Approximations to the CIE XYZ Color Matching Functions").
// lambda in nanometres.
double CIEXBar(double lambda);
double CIEYBar(double lambda);
double CIEZBar(double lambda);

// Linear sRGB from CIE XYZ (no chromatic adaptation; Y = 1 is unit luminance).
RGB XYZToRGB(double x, double y, double z);

// Converts a piecewise-linear spectrum given as (lambda nm, value) samples, following pbrt's
// RGBSpectrum::FromSampled: XYZ = ∫S·cmf dλ / ∫ybar dλ over 360–830 nm, then XYZ→RGB.
// Values outside the sampled range are clamped to the end samples. Unsorted input is sorted.
// An empty list gives black. Note that, as in pbrt-v3, a flat spectrum of 1 has XYZ ≈ (1,1,1)
// (illuminant E), which is slightly reddish in sRGB: about (1.20, 0.95, 0.91).
RGB SampledToRGB(std::vector<std::pair<double, double>> samples);

// pbrt-v3 "blackbody" [T scale]: Planck's law for temperature T (kelvin) normalized so its peak
// (at Wien's wavelength, as pbrt-v3 BlackbodyNormalized) is 1, converted as SampledToRGB and
// multiplied by scale. T <= 0 or non-finite gives black.
RGB BlackbodyToRGB(double temperatureK, double scale = 1.0);

// Reads a .spd spectrum file (whitespace- or comma-separated (lambda nm, value) pairs, '#'
// comments) through the shared file reader and converts it as SampledToRGB. On failure returns
// nothing and sets *error to what went wrong, naming the file as `displayName`:
// `cannot open spectrum file "NAME": REASON` or
// `cannot read spectrum file "NAME": expected (wavelength, value) pairs`.
// With a budget (--max-memory) the file is size-checked before it is read: reading and
// converting it takes up to kSpdBytesPerFileByte times its size for a moment (the text, then
// a double for every two bytes, twice), and a file that would not fit in what remains is a
// MemoryBudgetError at `loc`, `spectrum file "NAME" needs about ...` (nothing read).
inline constexpr uint64_t kSpdBytesPerFileByte = 10;
std::optional<RGB> ReadSpdFile(const std::string &path, const std::string &displayName,
                               std::string *error, const MemoryBudget *budget = nullptr,
                               const FileLoc &loc = {});

}  // namespace prism
