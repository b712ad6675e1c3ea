// pbrt-v3's defaults that more than one module needs, defined once.
#pragma once

namespace prism {

inline constexpr int PbrtDefaultXResolution = 1280;  // Film "xresolution"
inline constexpr int PbrtDefaultYResolution = 720;   // Film "yresolution"
inline constexpr float PbrtDefaultFovDeg = 90;       // perspective Camera "fov"

}  // namespace prism
