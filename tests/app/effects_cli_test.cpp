// `prism info` lists the effect set with reasons; `prism render --effects all` runs the general
// kernel and writes the same image as the specialized one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/process.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

bool Has(const std::string &out, const std::string &s) { return out.find(s) != std::string::npos; }

TEST(EffectsCli, InfoListsEveryEffectWithReasons) {
    fs::path dir = TempDir("info");
    RunResult r = RunPrism("info '" + Source + "/scenes/whitted.pbrt'", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string &o = r.out;
    EXPECT_TRUE(Has(o, "  shadows: on (LightSource \"point\" at ")) << o;
    EXPECT_TRUE(Has(o, "  specular reflection: on (material \"mirror\" at ")) << o;
    EXPECT_TRUE(Has(o, "whitted.pbrt:33:3)")) << o;
    EXPECT_TRUE(Has(o, "  refraction: on (material \"glass\" at ")) << o;
    EXPECT_TRUE(Has(o, "  glossy reflection: off (Integrator \"whitted\" traces no glossy rays)"))
        << o;
    EXPECT_TRUE(Has(o, "  environment: on (LightSource \"infinite\" at ")) << o;
    EXPECT_TRUE(Has(o, "  textures: on (")) << o;
    for (const char *off : {"soft shadows: off", "depth of field: off", "motion blur: off",
                            "CSG: off", "instancing: off"})
        EXPECT_TRUE(Has(o, off)) << off << "\n" << o;
    EXPECT_TRUE(Has(o, "4 shadow rays per shading point")) << o;
    EXPECT_TRUE(Has(o, "max useful depth: 6 (maxdepth 6)")) << o;
    EXPECT_TRUE(Has(o, "kernel:     specular+light samples+BSDF")) << o;

    r = RunPrism("info '" + Source + "/scenes/csg.pbrt'", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(Has(r.out, "  CSG: on (CSGBegin \"")) << r.out;

    r = RunPrism("info '" + Source + "/scenes/glossy.pbrt'", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(Has(r.out, "  glossy reflection: on (material \"metal\" at ")) << r.out;
    EXPECT_TRUE(Has(r.out, "  glossy transmission: on (material \"glass\" at ")) << r.out;
    EXPECT_TRUE(Has(r.out, "  soft shadows: on (AreaLightSource \"diffuse\" at ")) << r.out;

    r = RunPrism("info '" + Source + "/scenes/diffuse.pbrt'", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(Has(r.out, "  specular reflection: off\n")) << r.out;
    EXPECT_TRUE(Has(r.out, "max useful depth: 1 (maxdepth 5)")) << r.out;
    EXPECT_TRUE(Has(r.out, "kernel:     Lambertian")) << r.out;

    // An OBJ: the distribution integrator; a specular (mirror) material.
    std::ofstream(dir / "m.mtl") << "newmtl m\nKd 0 0 0\nKs 0.9 0.9 0.9\nillum 3\n"
                                    "newmtl d\nKd 0.5 0.5 0.5\n";
    std::ofstream(dir / "m.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                    "usemtl d\nf 1 2 3\nusemtl m\nf 1 3 4\n";
    r = RunPrism("info m.obj", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(Has(r.out, "  shadows: ")) << r.out;
    EXPECT_TRUE(Has(r.out, "max useful depth: ")) << r.out;
    EXPECT_FALSE(Has(r.out, "(Integrator \"distribution\" traces no glossy rays)")) << r.out;
}

TEST(EffectsCli, RenderEffectsAllWritesTheSameImage) {
    fs::path dir = TempDir("render");
    const std::string scene = "'" + Source + "/scenes/whitted.pbrt' --res 40x30 --spp 1";
    RunResult a = RunPrism("render " + scene + " -o spec.pfm --no-progress", dir);
    ASSERT_EQ(a.exitCode, 0) << a.err;
    EXPECT_TRUE(Has(a.err, "kernel: specular+light samples+BSDF")) << a.err;
    RunResult b = RunPrism("render " + scene + " --effects all -o all.pfm --no-progress", dir);
    ASSERT_EQ(b.exitCode, 0) << b.err;
    EXPECT_TRUE(Has(b.err, "kernel: all")) << b.err;
    EXPECT_EQ(ReadFile(dir / "spec.pfm"), ReadFile(dir / "all.pfm"));
    EXPECT_NE(RunPrism("render " + scene + " --effects some -o x.pfm", dir).exitCode, 0);
}

// prism batch passes --effects on to its renders.
TEST(EffectsCli, BatchPassesEffectsOn) {
    fs::path dir = TempDir("batch");
    fs::create_directories(dir / "in");
    fs::copy_file(Source + "/scenes/diffuse.pbrt", dir / "in" / "d.pbrt");
    RunResult r = RunPrism("batch in -o out --quiet --res 32x24 --effects all --format exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "out" / "in_d.exr"));
    EXPECT_NE(RunPrism("batch in -o out2 --effects none", dir).exitCode, 0);
}

}  // namespace
}  // namespace prism
