// Scene and file text more than one test file writes. No GoogleTest here: the fuzz targets
// use it too.
#pragma once

#include <cstring>
#include <initializer_list>
#include <string>

namespace prism::test {

// Appends each value's bytes to `buf` (binary buffers for glTF files).
template <typename T>
void PutBytes(std::string &buf, std::initializer_list<T> values) {
    for (T v : values) {
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        buf.append(b, sizeof(T));
    }
}

// `s` with its first `from` replaced by `to` (unchanged when there is none).
std::string ReplaceFirst(std::string s, const std::string &from, const std::string &to);

// `bin` in base64 (RFC 4648, padded), for glTF data URIs.
std::string Base64(const std::string &bin);

// An ASCII PLY of `nv` vertices on the z axis and one triangle.
std::string AsciiPly(int nv);

// The first five lines of the CLI tests' scenes (an 8 x 8 camera looking down -z at the origin
// from z = 5, and a point light at the camera); what a case adds starts on line 6.
extern const char *const kCliHead;

// pbrt-v3 text from "LookAt" on: a camera looking at a 6 x 6 floor (matte 0.6 0.5 0.4) lit by a
// point light and a small square area light; the caller adds its own shapes after it (the
// material state is the floor's). For the integrators' tests of a plainly lit diffuse scene.
extern const char *const kLitFloorFromLookAt;

// A pbrt Shape: the six inward faces of the box [-2, 2] x [0, 4] x [-2, 2] (floor, walls and
// ceiling) as one triangle mesh, in the current material. The bidirectional integrators' rooms.
extern const char *const kClosedRoom;

}  // namespace prism::test
