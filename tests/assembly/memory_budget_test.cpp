// BuildRenderScene charges the render's one MemoryBudget (BuildSettings::budget) with the film
// (EstimateFilmBytes), decoded image textures, triangle meshes and the BVH estimate
// (EstimateBvhBytes), on top of what LoadScene charged: items each under the limit but together
// over it are refused with a MemoryBudgetError that names the budget and no command-line flag.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "assembly/build_scene.h"
#include "core/memory.h"
#include "image/image_io.h"
#include "render/renderer.h"
#include "scene/pbrt_parser.h"
#include "scene/ply_reader.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

const ScratchFiles kFiles("prism_assembly_budget");

// A 64x64 film with the box filter (radius 0.5), one light, and `world`.
SceneDescription Parse(const std::string &world, Diagnostics &diag) {
    return ParsePbrtString(
        "Film \"image\" \"integer xresolution\" [64] \"integer yresolution\" [64]\n"
        "PixelFilter \"box\"\nWorldBegin\nLightSource \"point\"\n" +
            world,
        kFiles.Path("budget.pbrt"), diag);
}
const uint64_t FilmBytes = EstimateFilmBytes(64, 64, 0.5, 0.5, RenderTileSize);

// Builds `d` with `budget`; the MemoryBudgetError it throws, or nullopt.
std::optional<MemoryBudgetError> BuildError(const SceneDescription &d, MemoryBudget &budget) {
    Diagnostics diag;
    BuildSettings s;
    s.budget = &budget;
    try {
        BuildRenderScene(d, s, diag);
    } catch (const MemoryBudgetError &e) {
        return e;
    }
    return std::nullopt;
}

// A trianglemesh of `n` separate triangles (3n vertices).
std::string Triangles(int n) {
    std::string P, idx;
    for (int i = 0; i < n; ++i) {
        P +=
            std::to_string(i) + " 0 0 " + std::to_string(i) + " 1 0 " + std::to_string(i) + " 0 1 ";
        idx += std::to_string(3 * i) + " " + std::to_string(3 * i + 1) + " " +
               std::to_string(3 * i + 2) + " ";
    }
    return "Shape \"trianglemesh\" \"point3 P\" [" + P + "] \"integer indices\" [" + idx + "]\n";
}

TEST(BuildBudget, FilmEstimateIsChargedWithTheTileMargins) {
    // 64 x 64 pixels of 56 bytes (film, image, encoded copy) and 4 x 4 tiles of 17 x 17.
    EXPECT_EQ(FilmBytes, 64u * 64 * 56 + 68u * 68 * 32);
    Diagnostics diag;
    SceneDescription d = Parse("", diag);
    MemoryBudget budget(64 << 20);
    EXPECT_FALSE(BuildError(d, budget));
    EXPECT_EQ(budget.Used(), FilmBytes + EstimateBvhBytes(0, 0));
}

TEST(BuildBudget, FilmAndTextureEachUnderTheLimitAreRefusedTogether) {
    std::string png = kFiles.Path("tex128.png");
    WriteImage(png, Image(128, 128, 3));
    const uint64_t textureBytes = 128 * 128 * 3 * sizeof(float);
    Diagnostics diag;
    SceneDescription d =
        Parse("Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"" + png +
                  "\"\nMaterial \"matte\" \"texture Kd\" \"t\"\nShape \"sphere\"\n",
              diag);
    MemoryBudget budget(FilmBytes + textureBytes - 1);  // each fits, not both
    std::optional<MemoryBudgetError> e = BuildError(d, budget);
    ASSERT_TRUE(e);
    std::string msg = e->what();
    EXPECT_NE(msg.find("error: texture \"" + png + "\" needs about 192 KiB; with "),
              std::string::npos)
        << msg;
    EXPECT_NE(msg.find("already committed that exceeds the memory budget of"), std::string::npos)
        << msg;
    EXPECT_EQ(msg.find("--max-memory"), std::string::npos) << "the library names no flag: " << msg;
    EXPECT_EQ(e->Requested(), textureBytes);
    EXPECT_EQ(e->Committed(), FilmBytes);
    EXPECT_EQ(budget.Used(), FilmBytes);

    MemoryBudget enough(64 << 20);
    EXPECT_FALSE(BuildError(d, enough));
    // The texture's MIP levels above the image (EWA lookups, the default): 64², 32², ... 1²
    // RGB float texels.
    const uint64_t mipBytes = (64 * 64 + 32 * 32 + 16 * 16 + 8 * 8 + 4 * 4 + 2 * 2 + 1) * 12;
    EXPECT_EQ(enough.Used(), FilmBytes + textureBytes + mipBytes + EstimateBvhBytes(0, 1));
}

TEST(BuildBudget, FilmAndPlyMeshEachUnderTheLimitAreRefusedTogether) {
    const int n = 500;
    std::string ply = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(3 * n) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                      std::to_string(n) + "\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < n; ++i)
        ply += std::to_string(i) + " 0 0\n" + std::to_string(i) + " 1 0\n" + std::to_string(i) +
               " 0 1\n";
    for (int i = 0; i < n; ++i)
        ply += "3 " + std::to_string(3 * i) + " " + std::to_string(3 * i + 1) + " " +
               std::to_string(3 * i + 2) + "\n";
    std::string path = kFiles.Path("budget500.ply");
    std::ofstream(path, std::ios::binary) << ply;
    const uint64_t plyBytes = PlyMeshBytes(ply.size(), 3 * n, n);
    const uint64_t meshBytes = TriangleMesh::Bytes(3 * n, 3 * n, false, false);
    Diagnostics diag;
    SceneDescription d = Parse("Shape \"plymesh\" \"string filename\" \"" + path + "\"\n", diag);
    MemoryBudget budget(FilmBytes + plyBytes - 1);  // each fits, not both
    std::optional<MemoryBudgetError> e = BuildError(d, budget);
    ASSERT_TRUE(e);
    EXPECT_NE(std::string(e->what()).find("already committed that exceeds the memory budget of"),
              std::string::npos)
        << e->what();
    EXPECT_EQ(e->Requested(), plyBytes);
    EXPECT_EQ(e->Committed(), FilmBytes);

    // The PLY's arrays are given back once the render-space mesh is made; the mesh is kept.
    MemoryBudget enough(64 << 20);
    EXPECT_FALSE(BuildError(d, enough));
    EXPECT_EQ(enough.Used(), FilmBytes + meshBytes + EstimateBvhBytes(n, 0));
}

TEST(BuildBudget, MeshAndBvhEstimateAreCharged) {
    const int n = 1000;
    const uint64_t meshBytes = TriangleMesh::Bytes(3 * n, 3 * n, false, false);
    EXPECT_EQ(meshBytes, uint64_t(3 * n) * 12 + 4 + uint64_t(3 * n) * 4);
    Diagnostics diag;
    SceneDescription d = Parse(Triangles(n), diag);
    const uint64_t total = FilmBytes + meshBytes + EstimateBvhBytes(n, 0);
    MemoryBudget enough(total);
    EXPECT_FALSE(BuildError(d, enough));
    EXPECT_EQ(enough.Used(), total);

    // One byte less: the BVH, charged last, is refused before Embree builds it.
    MemoryBudget tight(total - 1);
    std::optional<MemoryBudgetError> e = BuildError(d, tight);
    ASSERT_TRUE(e);
    EXPECT_NE(std::string(e->what()).find("BVH needs about"), std::string::npos) << e->what();
    EXPECT_EQ(e->Requested(), EstimateBvhBytes(n, 0));
    EXPECT_EQ(e->Requested(), n * kBvhBytesPerTriangle + kBvhFixedBytes);

    // The mesh itself is refused before it is allocated when the film leaves too little.
    MemoryBudget small(FilmBytes + meshBytes - 1);
    e = BuildError(d, small);
    ASSERT_TRUE(e);
    EXPECT_NE(std::string(e->what()).find("shape \"trianglemesh\" needs about"), std::string::npos)
        << e->what();
}

TEST(BuildBudget, InstancedPrototypeTrianglesCountOnceAndEachInstanceAsOnePrimitive) {
    const int n = 200;
    const uint64_t meshBytes = TriangleMesh::Bytes(3 * n, 3 * n, false, false);
    Diagnostics diag;
    SceneDescription d = Parse("ObjectBegin \"o\"\n" + Triangles(n) +
                                   "ObjectEnd\nObjectInstance \"o\"\nTranslate 1 0 0\n"
                                   "ObjectInstance \"o\"\nTranslate 1 0 0\nObjectInstance \"o\"\n",
                               diag);
    MemoryBudget budget(64 << 20);
    EXPECT_FALSE(BuildError(d, budget));
    EXPECT_EQ(budget.Used(), FilmBytes + meshBytes + EstimateBvhBytes(n, 3));
}

TEST(BuildBudget, WithoutABudgetTheDefaultLimitApplies) {
    Diagnostics diag;
    SceneDescription d = Parse(Triangles(2), diag);
    BuildSettings s;  // budget null: a budget of its own of the default limit
    EXPECT_NO_THROW(BuildRenderScene(d, s, diag));
    // The smallest square film over the default limit (75% of RAM) is refused before anything
    // is allocated, by a budget of that limit.
    int side = 1024;
    while (EstimateFilmBytes(uint64_t(side), uint64_t(side), 0.5, 0.5, RenderTileSize) <=
           DefaultMemoryBudget())
        side += side / 8;
    s.resolution = {side, side};
    try {
        BuildRenderScene(d, s, diag);
        ADD_FAILURE() << "a " << side << "x" << side << " film was not refused";
    } catch (const MemoryBudgetError &e) {
        EXPECT_EQ(e.Limit(), DefaultMemoryBudget());
    }
}

}  // namespace
}  // namespace prism
