// The memory budget counts cumulatively across the scene readers: the top-level file, every
// Include, PLY meshes, trianglemesh parameters, OBJ and glTF geometry are charged to one
// MemoryBudget (core/memory.h), so items each under the limit but together over it are refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "core/memory.h"
#include "scene/gltf_reader.h"
#include "scene/load_scene.h"
#include "scene/obj_reader.h"
#include "scene/ply_reader.h"
#include "support/errors.h"
#include "support/shared.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

const ScratchFiles kFiles("prism_memory_budget");

// A pbrt file of exactly `bytes` bytes: `body`, then comment lines.
std::string PaddedPbrt(const std::string &body, size_t bytes) {
    std::string s = body;
    while (s.size() + 62 <= bytes) s += "# " + std::string(59, 'x') + "\n";
    s += "#" + std::string(bytes - s.size() - 2, 'y') + "\n";
    EXPECT_EQ(s.size(), bytes);
    return s;
}

// The MemoryBudgetError `f` throws ("" if none; "not a MemoryBudgetError" for another error).

TEST(MemoryBudgetScene, IncludedFilesEachUnderTheLimitAreRefusedTogether) {
    kFiles.Write("part_a.pbrt", PaddedPbrt("", 3000));
    kFiles.Write("part_b.pbrt", PaddedPbrt("", 3000));
    std::string top = kFiles.Write("two_parts.pbrt",
                                   "Camera \"perspective\"\nWorldBegin\n"
                                   "Include \"part_a.pbrt\"\nInclude \"part_b.pbrt\"\n");
    std::string onlyA = kFiles.Write("one_part.pbrt", "WorldBegin\nInclude \"part_a.pbrt\"\n");
    const uint64_t topSize = fs::file_size(top);
    Diagnostics diag;
    LoadOptions opts;
    opts.maxMemory = 5000;
    // Each part fits the budget with its top file.
    EXPECT_NO_THROW(LoadScene(onlyA, diag, opts));
    // Both together do not: refused at the second Include, naming both sums and the limit.
    std::string err = ErrorOf<MemoryBudgetError>([&] { LoadScene(top, diag, opts); });
    EXPECT_NE(err.find("two_parts.pbrt:4:1: error: included file \"part_b.pbrt\" needs about "
                       "2.9 KiB; with "),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("already committed that exceeds the memory budget of 4.9 KiB"),
              std::string::npos)
        << err;
    EXPECT_EQ(err.find("--max-memory"), std::string::npos) << err;

    // A budget passed in is charged and keeps its charges for the builder.
    MemoryBudget budget(1 << 20);
    opts.budget = &budget;
    EXPECT_NO_THROW(LoadScene(top, diag, opts));
    EXPECT_GE(budget.Used(), topSize + 6000);
    EXPECT_LT(budget.Used(), topSize + 6000 + 1000);
}

TEST(MemoryBudgetScene, TheTopFileCountsWithWhatIsAlreadyCommitted) {
    std::string path = kFiles.Write("top.pbrt", PaddedPbrt("WorldBegin\n", 2000));
    MemoryBudget budget(5000);
    budget.Charge(4000, "film");
    Diagnostics diag;
    LoadOptions opts;
    opts.budget = &budget;
    std::string err = ErrorOf<MemoryBudgetError>([&] { LoadScene(path, diag, opts); });
    EXPECT_NE(err.find("scene file needs about 2.0 KiB; with 3.9 KiB already committed that "
                       "exceeds the memory budget of 4.9 KiB"),
              std::string::npos)
        << err;
    EXPECT_EQ(budget.Used(), 4000u);
}

TEST(MemoryBudgetScene, PlyUnderTheLimitWithTheSceneFileOverIt) {
    std::string ply = kFiles.Write("mesh.ply", AsciiPly(200));
    const uint64_t meshBytes = PlyMeshBytes(fs::file_size(ply), 200, 1);
    std::string scene = kFiles.Write("with_mesh.pbrt",
                                     PaddedPbrt("WorldBegin\nShape \"plymesh\" \"string filename\" "
                                                "\"mesh.ply\"\n",
                                                3000));
    const uint64_t limit = meshBytes + 2000;  // the mesh alone fits, not with the scene file
    Diagnostics diag;
    {
        MemoryBudget budget(limit);
        EXPECT_EQ(ReadPlyFile(ply, diag, budget).P.size(), 200u);
        EXPECT_EQ(budget.Used(), meshBytes);
    }
    MemoryBudget budget(limit);
    LoadOptions opts;
    opts.budget = &budget;
    SceneDescription desc = LoadScene(scene, diag, opts);
    EXPECT_GE(budget.Used(), 3000u);
    // What the builder does for the "plymesh" shape: refused before the arrays are allocated.
    std::string err = ErrorOf<MemoryBudgetError>([&] { ReadPlyFile(ply, diag, budget); });
    EXPECT_NE(err.find("mesh.ply:3:1: error: mesh needs about"), std::string::npos) << err;
    EXPECT_NE(err.find("already committed that exceeds the memory budget of"), std::string::npos)
        << err;
}

TEST(MemoryBudgetScene, TopLevelPlyIsCheckedAndItsChargeGivenBack) {
    std::string ply = kFiles.Write("top.ply", AsciiPly(200));
    const uint64_t meshBytes = PlyMeshBytes(fs::file_size(ply), 200, 1);
    Diagnostics diag;
    MemoryBudget budget(meshBytes + 100);
    LoadOptions opts;
    opts.budget = &budget;
    EXPECT_NO_THROW(LoadScene(ply, diag, opts));
    EXPECT_EQ(budget.Used(), 0u);  // the builder charges the mesh when it reads it again
    budget.Charge(200, "textures");
    std::string err = ErrorOf<MemoryBudgetError>([&] { LoadScene(ply, diag, opts); });
    EXPECT_NE(err.find("mesh needs about"), std::string::npos) << err;
    EXPECT_EQ(budget.Used(), 200u);
}

TEST(MemoryBudgetScene, TriangleMeshParametersAreCharged) {
    std::string points, indices;
    for (int i = 0; i < 300; ++i) points += "0 0 " + std::to_string(i) + " ";
    for (int i = 0; i < 100; ++i) indices += "0 1 2 ";
    std::string path =
        kFiles.Write("mesh.pbrt", "WorldBegin\nShape \"trianglemesh\" \"point P\" [" + points +
                                      "] \"integer indices\" [" + indices + "]\n");
    const uint64_t fileSize = fs::file_size(path);
    const uint64_t numbers = (900 + 300) * sizeof(double);  // P and indices, as doubles
    Diagnostics diag;
    MemoryBudget budget(1 << 20);
    LoadOptions opts;
    opts.budget = &budget;
    LoadScene(path, diag, opts);
    // The file, the mesh's numbers and the shape's description (ShapeDescBytes).
    const uint64_t shape = sizeof(ShapeDesc) + path.size() + 16;
    EXPECT_GE(budget.Used(), fileSize + numbers + sizeof(ShapeDesc));
    EXPECT_LT(budget.Used(), fileSize + numbers + shape + 1024);
    // The file fits and the mesh alone fits, the file and its mesh together do not.
    ASSERT_GT(fileSize, 1024u);
    opts.budget = nullptr;
    opts.maxMemory = numbers + shape + 1024;
    std::string err = ErrorOf<MemoryBudgetError>([&] { LoadScene(path, diag, opts); });
    EXPECT_NE(err.find("mesh.pbrt:2:1: error: shape \"trianglemesh\" needs about 1"),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("already committed"), std::string::npos) << err;
}

TEST(MemoryBudgetScene, ObjFileAndGeometryAreCharged) {
    std::string path = kFiles.Write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const uint64_t fileSize = fs::file_size(path);
    Diagnostics diag;
    MemoryBudget budget(1 << 20);
    ReadObjFile(path, diag, &budget);
    EXPECT_GT(budget.Used(), fileSize + 9 * sizeof(double));
    MemoryBudget tight(fileSize + 16);
    std::string err = ErrorOf<MemoryBudgetError>([&] { ReadObjFile(path, diag, &tight); });
    EXPECT_NE(err.find("tri.obj: error: mesh needs about"), std::string::npos) << err;
}

TEST(MemoryBudgetScene, GltfBufferRefusedWithWhatIsCommitted) {
    kFiles.Write("tri2.bin", std::string(36, '\0'));
    std::string path = kFiles.Write(
        "tri2.gltf",
        R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "buffers": [{"byteLength": 36, "uri": "tri2.bin"}]})");
    const uint64_t gltfSize = fs::file_size(path);
    Diagnostics diag;
    MemoryBudget budget(1 << 20);
    ReadGltfFile(path, diag, budget);
    EXPECT_GT(budget.Used(), gltfSize + 36 + 9 * sizeof(double));
    // The .gltf and its buffer each fit; with 1000 bytes already committed they do not.
    MemoryBudget tight(gltfSize + 1010);
    tight.Charge(1000, "film");
    std::string err = ErrorOf<MemoryBudgetError>([&] { ReadGltfFile(path, diag, tight); });
    EXPECT_NE(err.find("tri2.gltf: error: file \"tri2.bin\" needs about 36 bytes; with "),
              std::string::npos)
        << err;
}

}  // namespace
}  // namespace prism
