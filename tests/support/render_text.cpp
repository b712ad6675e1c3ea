#include "support/render_text.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstdio>
#include <filesystem>
#include <utility>

#include "scene/load_scene.h"
#include "scene/pbrt_parser.h"
#include "support/temp_dir.h"

namespace prism::test {

Built BuildSceneFile(const std::string &path, const BuildSettings &opts) {
    Diagnostics diag;
    SceneDescription desc = LoadScene(path, diag);
    Built b;
    b.scene = BuildRenderScene(desc, opts, diag);
    b.warnings = diag.Warnings();
    return b;
}

Rendered RenderSceneFile(const std::string &path, const BuildSettings &opts) {
    Built b = BuildSceneFile(path, opts);
    Rendered r;
    r.scene = std::move(b.scene);
    r.warnings = std::move(b.warnings);
    r.image = Render(r.scene, &r.stats);
    return r;
}

std::string WriteSceneText(const std::string &dir, const std::string &name,
                           const std::string &text) {
    std::string file = std::filesystem::path(name).has_extension() ? name : name + ".pbrt";
    return WriteTestFile(ScratchDir(dir) / file, text);
}

RenderScene BuildSceneText(const std::string &dir, const std::string &name, const std::string &text,
                           const BuildSettings &opts) {
    return BuildSceneFile(WriteSceneText(dir, name, text), opts).scene;
}

Rendered RenderSceneText(const std::string &dir, const std::string &name, const std::string &text,
                         const BuildSettings &opts) {
    return RenderSceneFile(WriteSceneText(dir, name, text), opts);
}

BuildSettings SizedSettings(int w, int h, int spp, const std::string &integrator) {
    BuildSettings s;
    s.resolution = Vec2i(w, h);
    s.spp = spp;
    s.integrator = integrator;
    return s;
}

Image RenderWithSeed(const RenderScene &scene, uint32_t seed, RenderStats *stats) {
    RenderOptions o;
    o.sampler = scene.sampler;
    o.sampler.seed = seed;
    RenderStats own;
    return Render(scene, o, stats ? stats : &own);
}

Image RenderOnThreads(const RenderScene &scene, int threads) {
    Image img;
    RenderStats stats;
    tbb::task_arena(threads).execute([&] { img = Render(scene, &stats); });
    return img;
}

const Material &BuildSphereMaterial(const std::string &world, Diagnostics &diag,
                                    RenderScene &keep) {
    SceneDescription d = ParsePbrtString(
        "Camera \"perspective\"\nWorldBegin\nLightSource \"point\" \"rgb I\" [1 1 1]\n" + world +
            "Shape \"sphere\"\n",
        "test.pbrt", diag);
    BuildSettings o;
    o.resolution = {8, 8};
    keep = BuildRenderScene(d, o, diag);
    return keep.materials[size_t(keep.shapes[0].material)];
}

std::string LitSphereScene(const std::string &material, int spp, float sky) {
    std::string skyLine;
    if (sky > 0) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", double(sky));
        const std::string v = buf;
        skyLine = "LightSource \"infinite\" \"rgb L\" [" + v + " " + v + " " + v + "]\n";
    }
    return "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\n"
           "Film \"image\" \"integer xresolution\" 32 \"integer yresolution\" 32\n"
           "Sampler \"random\" \"integer pixelsamples\" " +
           std::to_string(spp) + "\nIntegrator \"path\" \"integer maxdepth\" 8\nWorldBegin\n" +
           skyLine +
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [10 10 10]\n"
           "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
           "  \"point P\" [-1 2 -1  1 2 -1  1 2 1  -1 2 1]\nAttributeEnd\n" +
           material + "\nShape \"sphere\" \"float radius\" 0.8\nWorldEnd\n";
}

void ExpectMaterialErrors(const std::string &type, const std::vector<std::string> &bad,
                          const std::string &fragment) {
    for (const std::string &b : bad) {
        Diagnostics diag;
        RenderScene keep;
        try {
            BuildSphereMaterial("Material \"" + type + "\" " + b + "\n", diag, keep);
            ADD_FAILURE() << type << " " << b;
        } catch (const SceneError &e) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("test.pbrt:4:"), std::string::npos) << e.what();
        }
    }
}

}  // namespace prism::test
