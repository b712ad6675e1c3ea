// Resource limits of the scene readers: the memory budget (LoadOptions::maxMemory, ReadPlyFile's
// maxBytes, ReadGltfFile's maxMemory), sizes that do not fit the file, and include depth/cycles.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scene/gltf_reader.h"
#include "scene/load_scene.h"
#include "scene/pbrt_parser.h"
#include "scene/ply_reader.h"
#include "support/errors.h"
#include "support/shared.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

const ScratchFiles kFiles("prism_limits");

TEST(Limits, PlyMeshMustFitTheMemoryBudget) {
    std::string path = kFiles.Write("budget.ply", AsciiPly(1000));
    Diagnostics diag;
    EXPECT_EQ(ReadPlyFile(path, diag, 1 << 20).P.size(), 1000u);
    std::string err = ErrorOf<SceneError>([&] { ReadPlyFile(path, diag, 20000); });
    EXPECT_NE(err.find("budget.ply:3:1: error: mesh needs about"), std::string::npos) << err;
    EXPECT_NE(err.find("more than the memory budget of 20 KiB"), std::string::npos) << err;
    EXPECT_EQ(err.find("--max-memory"), std::string::npos) << "the library names no flag: " << err;
    // The file itself larger than the budget.
    err = ErrorOf<SceneError>([&] { ReadPlyFile(path, diag, 1000); });
    EXPECT_NE(err.find("more than the memory budget of 1000 bytes"), std::string::npos) << err;
}

TEST(Limits, PlyHeaderClaimingATrillionVertices) {
    std::string path =
        kFiles.Write("trillion.ply",
                     "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\n"
                     "property float x\nproperty float y\nproperty float z\nend_header\n" +
                         std::string(24, '\0'));
    Diagnostics diag;
    std::string err = ErrorOf<SceneError>([&] { ReadPlyFile(path, diag); });
    EXPECT_NE(err.find("file ends after 2 of 1000000000000 vertices"), std::string::npos) << err;
}

TEST(Limits, LoadSceneRejectsFilesBeyondTheBudget) {
    std::string path = kFiles.Write("big.ply", AsciiPly(100));
    LoadOptions opts;
    opts.maxMemory = 100;
    Diagnostics diag;
    std::string err = ErrorOf<SceneError>([&] { LoadScene(path, diag, opts); });
    EXPECT_NE(err.find("more than the memory budget of 100 bytes"), std::string::npos) << err;
    EXPECT_EQ(err.find("--max-memory"), std::string::npos) << "the library names no flag: " << err;
    opts.maxMemory = 1 << 20;
    EXPECT_NO_THROW(LoadScene(path, diag, opts));
}

std::string TriangleGltf(const std::string &bufferUri, int byteLength) {
    return R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "buffers": [{"byteLength": )" +
           std::to_string(byteLength) + R"(, "uri": ")" + bufferUri + R"("}]})";
}

TEST(Limits, GltfBuffersMustFitTheBudgetAndBeRegularFiles) {
    kFiles.Write("tri.bin", std::string(36, '\0'));
    std::string path = kFiles.Write("tri.gltf", TriangleGltf("tri.bin", 36));
    Diagnostics diag;
    EXPECT_NO_THROW(ReadGltfFile(path, diag, 1 << 20));
    // The .gltf itself fits but the buffer does not.
    uint64_t gltfSize = fs::file_size(path);
    std::string err = ErrorOf<SceneError>([&] { ReadGltfFile(path, diag, gltfSize + 10); });
    EXPECT_NE(err.find("exceeds the memory budget"), std::string::npos) << err;
    // A buffer that is a device (hostile URI) is refused before it is read.
    std::string rel;
    for (fs::path p = kFiles.Dir(); p.has_relative_path() && p != p.root_path();
         p = p.parent_path())
        rel += "../";
    path = kFiles.Write("zero.gltf", TriangleGltf(rel + "dev/zero", 36));
    err = ErrorOf<SceneError>([&] { ReadGltfFile(path, diag); });
    EXPECT_NE(err.find("not a regular file"), std::string::npos) << err;
}

TEST(Limits, GltfAccessorPastItsBuffer) {
    kFiles.Write("short.bin", std::string(24, '\0'));
    std::string path = kFiles.Write("short.gltf", TriangleGltf("short.bin", 24));
    Diagnostics diag;
    std::string err = ErrorOf<SceneError>([&] { ReadGltfFile(path, diag); });
    EXPECT_NE(err.find("reaches past the end of its buffer"), std::string::npos) << err;
}

TEST(Limits, IncludeDepthAndCycles) {
    // a0 includes a1 includes ... a9: fine with depth 10, an error with depth 5.
    for (int i = 0; i < 10; ++i)
        kFiles.Write(
            "chain" + std::to_string(i) + ".pbrt",
            i < 9 ? "Include \"chain" + std::to_string(i + 1) + ".pbrt\"\n" : "Shape \"sphere\"\n");
    Diagnostics diag;
    PbrtParseOptions opts;
    opts.maxIncludeDepth = 10;
    EXPECT_NO_THROW(ParsePbrtFile(kFiles.Path("chain0.pbrt"), diag, opts));
    opts.maxIncludeDepth = 5;
    std::string err =
        ErrorOf<SceneError>([&] { ParsePbrtFile(kFiles.Path("chain0.pbrt"), diag, opts); });
    EXPECT_NE(err.find("includes nested deeper than"), std::string::npos) << err;
    kFiles.Write("self.pbrt", "WorldBegin\nInclude \"self.pbrt\"\n");
    err = ErrorOf<SceneError>([&] { ParsePbrtFile(kFiles.Path("self.pbrt"), diag); });
    EXPECT_NE(err.find("self.pbrt:2:1: error: include cycle"), std::string::npos) << err;
    // Confined includes may not leave the top-level file's directory.
    kFiles.Write("escape.pbrt", "Include \"../escape-target.pbrt\"\n");
    std::ofstream(kFiles.Dir().parent_path() / "escape-target.pbrt") << "\n";
    opts.confineIncludes = true;
    err = ErrorOf<SceneError>([&] { ParsePbrtFile(kFiles.Path("escape.pbrt"), diag, opts); });
    EXPECT_NE(err.find("escape.pbrt:1:1: error:"), std::string::npos) << err;
}

}  // namespace
}  // namespace prism
