// Entry points shared by the libFuzzer targets (tests/fuzz/fuzz_*.cpp) and the regression test
// that replays tests/fuzz/regressions/ in the ordinary build: one function per reader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace prism::fuzz {

// Each feeds `data` to one reader. Expected rejections (SceneError, and the runtime_error the
// image reader documents) are caught, their message stored in *rejected if given (which is
// left alone when the input is accepted); anything else — a crash, a sanitizer report, another
// exception type such as std::bad_alloc — escapes and is a bug.
void FuzzPbrt(const uint8_t *data, size_t size,
              std::string *rejected = nullptr);  // ParsePbrtString, includes confined
void FuzzPly(const uint8_t *data, size_t size, std::string *rejected = nullptr);  // ReadPlyFile
void FuzzStl(const uint8_t *data, size_t size, std::string *rejected = nullptr);  // ReadStlFile
void FuzzObj(const uint8_t *data, size_t size,
             std::string *rejected = nullptr);  // ReadObjFile (+ MTL after a "#%MTL" line)
void FuzzGltf(const uint8_t *data, size_t size,
              std::string *rejected = nullptr);  // ReadGltfFile: .glb if it starts with "glTF"
void FuzzImage(const uint8_t *data, size_t size,
               std::string *rejected = nullptr);  // ReadImageFromMemory
void FuzzBsdf(const uint8_t *data, size_t size,
              std::string *rejected = nullptr);  // FourierTable::Parse, then f, Pdf, Sample

// Structure-aware (fuzz_structured.cpp): the bytes are a generator's choices, not the file.
void FuzzGltfJson(const uint8_t *data, size_t size,
                  std::string *rejected = nullptr);  // a well-formed glTF → ReadGltfFile
void FuzzTextureGraph(const uint8_t *data, size_t size,
                      std::string *rejected = nullptr);  // a texture graph → build and render
// The files those two make of `data` (to read or reproduce a finding).
std::string GltfJsonScene(const uint8_t *data, size_t size);
std::string TextureGraphScene(const uint8_t *data, size_t size);

// Dispatch by target name ("pbrt", "ply", "stl", "obj", "gltf", "image", "bsdf", "gltf_json",
// "texture");
// false if unknown.
bool FuzzByName(const std::string &target, const uint8_t *data, size_t size,
                std::string *rejected = nullptr);

}  // namespace prism::fuzz
