// `prism info SCENE`: what a scene file contains, without building a BVH.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>

#include "app/commands.h"
#include "app/common.h"
#include "assembly/build_scene.h"
#include "assembly/shape_factory.h"
#include "core/file_io.h"
#include "core/pbrt_defaults.h"
#include "render/kernel.h"
#include "scene/load_scene.h"

namespace prism {

namespace {

struct InfoArgs {
    std::string scene, maxMemory, pbrtVersion;
    ConfineOption confine;
};

// Names from the scene (types, filter names) reach the terminal escaped, as every error and
// warning does (EscapeControlChars, core/error.h): an escape sequence in a name could clear the
// screen or set the window title.
std::string Counts(const std::map<std::string, int> &m) {
    std::string s;
    for (const auto &[k, v] : m)
        s += (s.empty() ? "" : ", ") + EscapeControlChars(k) + " " + std::to_string(v);
    return s.empty() ? "none" : s;
}

// Every effect on or off, with the reason (and location) of each one on; each light's shadows;
// the maximum useful depth; the kernel the renderer runs.
void PrintEffects(const RenderScene &scene) {
    const EffectSet &e = scene.features.effects;
    std::printf("effects:\n");
    for (size_t i = 0; i < size_t(Effect::Count); ++i) {
        const Effect eff = Effect(i);
        if (e.Has(eff))
            std::printf("  %s: on (%s)\n", EffectName(eff),
                        EscapeControlChars(e.reasons[i]).c_str());
        else if ((eff == Effect::GlossyReflection || eff == Effect::GlossyTransmission) &&
                 !scene.integrator->Traits().roughGlass)
            std::printf("  %s: off (Integrator \"%s\" traces no glossy rays)\n", EffectName(eff),
                        scene.IntegratorName());
        else
            std::printf("  %s: off\n", EffectName(eff));
    }
    for (const LightShadows &l : e.lights)
        std::printf("  shadows of %s: %d shadow ray%s per shading point\n",
                    EscapeControlChars(l.light).c_str(), l.shadowRays,
                    l.shadowRays == 1 ? "" : "s");
    std::printf("max useful depth: %d (maxdepth %d)\n", e.maxUsefulDepth, scene.trace.maxDepth);
    if (scene.integrator->Traits().effectKernel)
        std::printf("kernel:     %s\n", KernelMaskName(KernelMaskFor(scene)).c_str());
    else  // the other integrators trace each camera sample through their Li
        std::printf("kernel:     none (%s integrator)\n", scene.IntegratorName());
}

int RunInfo(const InfoArgs &a) {
    ScopedReadConfinement confined(ConfinementFolderFor(a.confine, a.scene));
    Diagnostics diag(false);
    auto t0 = std::chrono::steady_clock::now();
    // One budget (--max-memory) for the scene and, one at a time, each mesh it counts.
    MemoryBudget budget(ParseMaxMemory(a.maxMemory));
    LoadOptions loadOpts;
    loadOpts.budget = &budget;
    loadOpts.pbrt.pbrtVersion = PbrtVersionNumber(a.pbrtVersion);
    SceneDescription desc = LoadScene(a.scene, diag, loadOpts);
    double loadSeconds = SecondsSince(t0);

    std::map<std::string, int> shapes, materials, textures, lights;
    size_t triangles = 0, curveSegments = 0;
    Bounds3d bounds;
    ShapeFactoryContext ctx{desc, diag, Precision::Double, &budget};
    auto account = [&](const ShapeDesc &s, const Transform &worldFromObject) {
        shapes[s.type]++;
        uint64_t usedBefore = budget.Used();
        ShapeGeometry g = CreateShapeGeometry(s, worldFromObject, ctx);
        struct GiveBack {  // the mesh is freed when this shape is counted
            MemoryBudget &b;
            uint64_t n;
            ~GiveBack() { b.Release(n); }
        } giveBack{budget, budget.Used() - usedBefore};
        if (g.mesh) {
            triangles += g.mesh->NumTriangles();
            Bounds3f b = g.mesh->RenderBounds();
            if (!b.IsEmpty()) bounds.Expand(Bounds3d(Vec3d(b.pMin), Vec3d(b.pMax)));
        } else if (g.analytic) {
            bounds.Expand(worldFromObject.Bounds(g.analytic->ObjectBounds()));
        } else if (g.curves) {
            curveSegments += g.curves->NumSegments();
            Bounds3f b = g.curves->RenderBounds();
            if (!b.IsEmpty()) bounds.Expand(Bounds3d(Vec3d(b.pMin), Vec3d(b.pMax)));
        }
    };
    for (const ShapeDesc &s : desc.shapes) account(s, s.worldFromObject);
    // CSG nodes (Prism extension): their operands are counted as shapes too.
    std::map<std::string, int> csgOps, csgOperands;
    std::function<void(const CsgDesc &)> countCsg = [&](const CsgDesc &node) {
        csgOps[node.op]++;
        for (const ShapeDesc &s : node.shapes) {
            csgOperands[s.type]++;
            account(s, s.worldFromObject);
        }
        for (const CsgDesc &child : node.children) countCsg(child);
    };
    for (const CsgDesc &node : desc.csg) countCsg(node);
    for (const InstanceDesc &inst : desc.instances) {
        const ObjectDesc *obj = FindObject(desc, inst.object);
        if (!obj) continue;
        for (const ShapeDesc &s : obj->shapes)
            account(s, inst.worldFromInstance * s.worldFromObject);
    }
    // The rest of the build (camera, film, sampler, textures, materials, lights) without the
    // BVH, for the warnings only a build gives ("sampler \"halton\" is replaced ...").
    BuildSettings settings;
    settings.budget = &budget;
    settings.buildBvh = false;
    RenderScene built = BuildRenderScene(desc, settings, diag);
    for (const MaterialDesc &m : desc.materials) materials[m.type]++;
    for (const TextureDesc &t : desc.textures) textures[t.type]++;
    for (const LightDesc &l : desc.lights) lights[l.type]++;
    int areaShapes = 0;
    for (const ShapeDesc &s : desc.shapes) areaShapes += s.areaLight >= 0;

    std::printf("scene:      %s (%s), loaded in %.3f s\n", EscapeControlChars(a.scene).c_str(),
                desc.format.c_str(), loadSeconds);
    if (desc.format == "pbrt") {
        const PbrtVersionChoice &v = desc.pbrtVersion;
        std::printf("rules:      pbrt-v%d (%s%s)\n", v.version, EscapeControlChars(v.why).c_str(),
                    v.loc.Valid() ? (" at " + EscapeControlChars(v.loc.ToString())).c_str() : "");
        // A file that mixes the versions renders (Prism reads both); pbrt would refuse it.
        if (!v.conflict.empty())
            std::printf("            though %s at %s is not; --pbrt-version chooses\n",
                        EscapeControlChars(v.conflict).c_str(),
                        EscapeControlChars(v.conflictLoc.ToString()).c_str());
    }
    int operandShapes = 0;  // CSG operands
    for (const auto &[k, v] : csgOperands) operandShapes += v;
    std::printf("shapes:     %zu (%s)\n", desc.shapes.size() + size_t(operandShapes),
                Counts(shapes).c_str());
    if (!desc.csg.empty()) {
        int nodes = 0;
        for (const auto &[k, v] : csgOps) nodes += v;
        std::printf("csg:        %zu objects, %d nodes (%s) over %d operand shapes (%s)\n",
                    desc.csg.size(), nodes, Counts(csgOps).c_str(), operandShapes,
                    Counts(csgOperands).c_str());
    }
    std::printf("triangles:  %zu\n", triangles);
    if (curveSegments > 0) std::printf("curves:     %zu segments\n", curveSegments);
    std::printf("instances:  %zu of %zu objects\n", desc.instances.size(), desc.objects.size());
    std::printf("materials:  %zu (%s)\n", desc.materials.size(), Counts(materials).c_str());
    std::printf("textures:   %zu (%s)\n", desc.textures.size(), Counts(textures).c_str());
    // How textures filter (docs/MATERIALS.md): imagemap "filter" (or v3's "trilinear"; EWA by
    // default), 2-D checkerboard "aamode" (closedform by default).
    std::map<std::string, int> filters;
    for (const TextureDesc &t : desc.textures) {
        if (t.type == "imagemap") {
            std::string f = t.params.GetString("filter", "");
            if (f.empty()) f = t.params.GetBool("trilinear", false) ? "trilinear" : "ewa";
            filters["imagemap " + f]++;
        } else if (t.type == "checkerboard" && t.params.GetInt("dimension", 2) == 2) {
            filters["checkerboard " + t.params.GetString("aamode", "closedform")]++;
        }
    }
    if (!filters.empty())
        std::printf("filtering:  %s; ray differentials %s\n", Counts(filters).c_str(),
                    built.differentials ? "on" : "off");
    std::printf("lights:     %zu (%s); %d emissive shapes\n", desc.lights.size(),
                Counts(lights).c_str(), areaShapes);
    if (!bounds.IsEmpty())
        std::printf("bounds:     %s - %s\n", ToString(bounds.pMin).c_str(),
                    ToString(bounds.pMax).c_str());
    const CameraDesc &cam = desc.camera;
    Transform worldFromCamera = cam.cameraFromWorld.Inverse();
    std::printf(
        "camera:     %s, eye %s, looking along %s%s\n",
        cam.specified ? EscapeControlChars(cam.type).c_str() : "perspective (default)",
        ToString(worldFromCamera.Point(Vec3d(0, 0, 0))).c_str(),
        ToString(Normalize(worldFromCamera.Vector(Vec3d(0, 0, 1)))).c_str(),
        cam.params.Has("fov")
            ? (", fov " + std::to_string(cam.params.GetFloat("fov", PbrtDefaultFovDeg))).c_str()
            : "");
    std::printf("film:       %dx%d%s\n",
                desc.film.params.GetInt("xresolution", PbrtDefaultXResolution),
                desc.film.params.GetInt("yresolution", PbrtDefaultYResolution),
                desc.film.colorSpace == ColorSpaceId::SRGB
                    ? ""
                    : (std::string(", linear ") + ColorSpaceName(desc.film.colorSpace) +
                       " (the ColorSpace at its Film directive)")
                          .c_str());
    std::printf("integrator: %s (%s)\n", built.IntegratorName(),
                EscapeControlChars(built.integratorWhy).c_str());
    PrintEffects(built);
    std::vector<Warning> w = diag.Warnings();
    std::printf("warnings:   %zu\n", w.size());
    for (const Warning &x : w) std::printf("  %s\n", x.ToString().c_str());
    return ExitOk;
}

}  // namespace

void AddInfoCommand(CLI::App &app, int *exitCode) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App *cmd = app.add_subcommand("info", "Describe what a scene contains (no BVH build)");
    cmd->add_option("scene", args->scene, "Scene file")->required();
    AddConfineOption(cmd, &args->confine);
    AddPbrtVersionOption(cmd, &args->pbrtVersion);
    cmd->add_option("--max-memory", args->maxMemory,
                    "Memory budget, e.g. 512M or 8G (default: 75% of physical RAM); a scene that "
                    "needs more is refused");
    cmd->callback([args, exitCode] { *exitCode = RunGuarded([&] { return RunInfo(*args); }); });
}

}  // namespace prism
