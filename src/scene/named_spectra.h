// pbrt-v4's named spectra ("metal-Cu-eta", "glass-BK7", "stdillum-D65", ...), which a pbrt-v4
// file names where it would otherwise give a spectrum file, reduced to Prism's RGB.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/color.h"

namespace prism {

// Whether `name` is one of pbrt-v4's named spectra, built in or not.
bool IsNamedSpectrum(std::string_view name);

// The RGB of a built-in named spectrum, or nullopt (with *why saying so) for a name pbrt-v4
// has that Prism does not build in (MgO, TiO2) or a name that is not a named spectrum.
//  - metals' eta and k and glasses' index: the spectrum averaged against each of the sRGB
//    colour-matching functions, normalised so a constant spectrum keeps its value;
//  - illuminants: the illuminant's chromaticity at luminance 1 (pbrt-v4 normalises a light's
//    spectrum to luminance 1, so only the chromaticity reaches the image).
std::optional<RGB> NamedSpectrumRGB(std::string_view name, std::string *why = nullptr);

// The built-in names, in a fixed order (the docs' table and the tests).
std::vector<std::string> BuiltInSpectrumNames();

}  // namespace prism
