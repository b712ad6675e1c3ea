// pbrt-v3's lens description files (the realistic camera's "lensfile"): one interface per
// line, scene side first, four numbers each (radius of curvature, thickness, index of
// refraction, aperture diameter; millimetres), '#' comments. Read with bounds on every value
// and on the number of rows; errors name the file's line and column.
#pragma once

#include <string>
#include <vector>

#include "render/lens_system.h"

namespace prism {

// The most interfaces a lens file may list (real designs have a few dozen at most).
inline constexpr int MaxLensInterfaces = 256;

// Parses `text`, the contents of lens file `file` (named in errors), into interfaces in
// metres (aperture radii, not diameters). Throws SceneError at the offending line and column.
std::vector<LensInterface> ParseLensFile(const std::string &text, const std::string &file);

}  // namespace prism
