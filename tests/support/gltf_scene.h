// A glTF test scene more than one test binary renders: the unit quad with two uv sets and a
// texture (tests/assembly/gltf_lighting_test.cpp, tests/render/volpath_test.cpp).
#pragma once

#include <string>

namespace prism::test {

// The quad [0,1]^2 at z = 0 (normal +z) with TEXCOORD_0 u = x and TEXCOORD_1 u = 1 - x, one
// material given as JSON and the texture 0 = image "tex.png".
std::string GltfTwoUvQuad(const std::string &material);

// Writes an 8 x 8 image to `path`: white where x < 4, black elsewhere (or the other way).
void WriteHalfImage(const std::string &path, bool leftWhite = true);

}  // namespace prism::test
