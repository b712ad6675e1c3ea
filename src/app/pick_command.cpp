// `prism pick SCENE X Y [--json]`: the camera ray through the centre of pixel (X, Y) and what it
// hits (shape and material declarations, instance chain, world-space hit point, t, normals,
// uv), then the specular reflection and refraction rays the Whitted kernel would follow from
// there, a few bounces deep. Text by default; --json prints the same as one JSON object.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "app/commands.h"
#include "app/common.h"
#include "app/shape_lookup.h"
#include "assembly/build_scene.h"
#include "render/bsdf.h"
#include "scene/load_scene.h"

namespace prism {

namespace {

struct PickArgs {
    std::string scene, res, precision = "double";
    int x = 0, y = 0, bounces = 3;
    bool json = false, quiet = false;
};

std::string JsonString(const std::string &s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof(buf), "\\u%04x", unsigned(c));
            out += buf;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

std::string Num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.9g", v + 0.0);  // + 0.0 prints -0 as 0
    return buf;
}

std::string Vec(const Vec3d &v) { return "[" + Num(v.x) + ", " + Num(v.y) + ", " + Num(v.z) + "]"; }
std::string Vec(const Vec3f &v) { return Vec(Vec3d(v)); }

std::string LocJson(const FileLoc &loc) {
    return "{\"file\": " + JsonString(loc.file) + ", \"line\": " + std::to_string(loc.line) +
           ", \"column\": " + std::to_string(loc.column) + "}";
}

// One ray of the path tree and its hit, as text lines and as a JSON object.
struct Picker {
    const SceneDescription &desc;
    const RenderScene &scene;
    ShapeLookup lookup;
    Transform worldFromRender;
    int maxBounces;
    std::string text;

    Picker(const SceneDescription &d, const RenderScene &s, int bounces)
        : desc(d),
          scene(s),
          lookup(d, s),
          worldFromRender(s.renderFromWorld.Inverse()),
          maxBounces(bounces) {}

    // Traces `ray` (render space) and returns its JSON object; appends text lines.
    std::string Follow(Ray ray, const std::string &kind, int depth, const std::string &indent) {
        const Vec3d o = worldFromRender.Point(Vec3d(ray.o));
        std::string j = "{\"kind\": " + JsonString(kind) + ", \"depth\": " + std::to_string(depth) +
                        ", \"origin\": " + Vec(o) + ", \"direction\": " + Vec(ray.d);
        text += indent + kind + " ray: origin " + Vec(o) + ", direction " + Vec(ray.d) + "\n";
        SurfaceInteraction si;
        int passThrough = 0;
        bool hit = scene.accel->Intersect(ray, &si);
        // "none" materials: the ray continues as in the kernel.
        while (hit && scene.materials[size_t(scene.Info(si).material)].IsPassThrough() &&
               passThrough < 256) {
            ++passThrough;
            ray = si.SpawnRay(ray.d, scene.offset);
            hit = scene.accel->Intersect(ray, &si);
        }
        if (passThrough > 0) {
            j += ", \"passThrough\": " + std::to_string(passThrough);
            text += indent + "  passed through " + std::to_string(passThrough) +
                    " surface(s) with material \"none\"\n";
        }
        if (!hit) {
            text += indent + "  miss\n";
            return j + ", \"hit\": null}";
        }
        const ShapeDeclaration d = lookup.Find(si);
        const ShapeInfo &info = scene.Info(si);
        Vec3f ng = si.n;  // pbrt's orientation, as `prism trace` prints it
        if (si.instanceShape < 0)
            if (const TriangleMesh *mesh = scene.accel->Mesh(si.shape))
                ng = mesh->GeometricNormal(size_t(si.prim));
        const Vec3d p = worldFromRender.Point(Vec3d(si.p));
        std::string h = "{";
        if (d.shape) {
            h += "\"shape\": {\"type\": " + JsonString(d.shape->type) +
                 ", \"name\": " + JsonString(d.shape->name) +
                 ", \"id\": " + std::to_string(d.shapeId) + ", \"loc\": " + LocJson(d.shape->loc) +
                 "}";
            text += indent + "  shape: " + lookup.ShapeLabel(d.shapeId) + " (shape id " +
                    std::to_string(d.shapeId) + ")\n";
        } else {
            h += "\"shape\": {\"type\": " + JsonString(info.type) + "}";
            text += indent + "  shape: " + info.type + "\n";
        }
        const MaterialDesc *md = d.shape && d.shape->material >= 0
                                     ? &desc.materials[size_t(d.shape->material)]
                                     : nullptr;
        if (md) {
            h += ", \"material\": {\"type\": " + JsonString(md->type) +
                 ", \"name\": " + JsonString(md->name) +
                 ", \"id\": " + std::to_string(d.materialId) + ", \"loc\": " + LocJson(md->loc) +
                 "}";
            text += indent + "  material: " + lookup.MaterialLabel(d.materialId) +
                    " (material id " + std::to_string(d.materialId) + ")\n";
        } else {
            h += ", \"material\": {\"type\": \"matte\", \"name\": \"\", \"id\": 1, \"loc\": null}";
            text += indent + "  material: the default matte (material id 1)\n";
        }
        // The instance chain, outermost first (pbrt-v3 and Embree 3: one instance level; a CSG
        // node counts as a level of its own).
        std::string chain;
        auto link = [&](const std::string &what, const std::string &name, const FileLoc &loc) {
            if (!chain.empty()) chain += ", ";
            chain += "{\"kind\": " + JsonString(what) + ", \"name\": " + JsonString(name) +
                     ", \"loc\": " + LocJson(loc) + "}";
            text += indent + "  in " + what + (name.empty() ? "" : " \"" + name + "\"") + " at " +
                    loc.ToString() + "\n";
        };
        if (d.instance) link("ObjectInstance", d.instance->object, d.instance->loc);
        if (d.object) link("ObjectBegin", d.object->name, d.object->loc);
        if (d.csg) link("CSGBegin", d.csg->op, d.csg->loc);
        h += ", \"instanceChain\": [" + chain + "]";
        if (d.instanceId > 0) h += ", \"instanceId\": " + std::to_string(d.instanceId);
        h += ", \"primitive\": " + std::to_string(si.prim) + ", \"t\": " + Num(si.t) +
             ", \"distance\": " + Num(double(si.t) * double(Length(ray.d))) +
             ", \"point\": " + Vec(p) + ", \"geometricNormal\": " + Vec(ng) +
             ", \"shadingNormal\": " + Vec(si.ns) + ", \"uv\": [" + Num(si.uv.x) + ", " +
             Num(si.uv.y) + "]";
        text += indent + "  primitive " + std::to_string(si.prim) + ", t " + Num(si.t) + "\n" +
                indent + "  point " + Vec(p) + " (world space)\n" + indent + "  geometric normal " +
                Vec(ng) + ", shading normal " + Vec(si.ns) + "\n" + indent + "  uv [" +
                Num(si.uv.x) + ", " + Num(si.uv.y) + "]\n";
        // The specular lobes, as the Whitted kernel follows them (depth + 1 < maxdepth).
        std::string next;
        if (depth < maxBounces && depth + 1 < scene.trace.maxDepth) {
            const Material &mat = scene.materials[size_t(info.material)];
            BSDF bsdf = mat.GetBSDF(si, SurfaceTextureContext(si));
            for (int part = 0; part < bsdf.NumParts(); ++part) {
                Vec3f wi;
                RGB weight;
                auto add = [&](const char *what) {
                    if (!next.empty()) next += ", ";
                    next += Follow(si.SpawnRay(wi, scene.offset), what, depth + 1, indent + "    ");
                };
                if (bsdf.SampleSpecularReflection(part, si.wo, &wi, &weight)) add("reflection");
                if (bsdf.SampleSpecularTransmission(part, si.wo, &wi, &weight)) add("refraction");
            }
        }
        h += ", \"bounces\": [" + next + "]}";
        return j + ", \"hit\": " + h + "}";
    }
};

int RunPick(const PickArgs &a) {
    Diagnostics diag(!a.quiet);
    MemoryBudget budget(ParseMaxMemory(""));
    LoadOptions loadOpts;
    loadOpts.budget = &budget;
    SceneDescription desc = LoadScene(a.scene, diag, loadOpts);
    BuildSettings opts;
    opts.budget = &budget;
    opts.precision = ParsePrecision(a.precision);
    if (!a.res.empty()) opts.resolution = ParseResolution(a.res);
    RenderScene scene = BuildRenderScene(desc, opts, diag);
    if (a.x < 0 || a.y < 0 || a.x >= scene.resolution.x || a.y >= scene.resolution.y)
        throw UsageError("pixel (" + std::to_string(a.x) + ", " + std::to_string(a.y) +
                         ") is outside the " + std::to_string(scene.resolution.x) + "x" +
                         std::to_string(scene.resolution.y) + " image");
    // uv and tangents for every top-level shape (the render computes them only where a
    // material reads them); shapes inside instances keep what their materials need.
    for (int i = 0; i < scene.accel->NumShapes(); ++i)
        if (scene.shapes[size_t(i)].prototype < 0) scene.accel->SetSurfaceNeeds(i, NeedAll);
    // The pixel centre, no lens sample, time 0: the ray of a 1-spp render.
    Ray ray = scene.camera->GenerateRay(Vec2f(float(a.x) + 0.5f, float(a.y) + 0.5f),
                                        Vec2f(0.5f, 0.5f), 0.f);
    Picker picker(desc, scene, a.bounces);
    std::string path = picker.Follow(ray, "camera", 0, "");
    std::string out;
    if (a.json) {
        out = "{\"scene\": " + JsonString(a.scene) + ", \"pixel\": [" + std::to_string(a.x) + ", " +
              std::to_string(a.y) + "], \"resolution\": [" + std::to_string(scene.resolution.x) +
              ", " + std::to_string(scene.resolution.y) +
              "], \"space\": \"world\", \"ray\": " + path + "}\n";
    } else {
        out = "pixel (" + std::to_string(a.x) + ", " + std::to_string(a.y) + ") of " + a.scene +
              " (" + std::to_string(scene.resolution.x) + "x" + std::to_string(scene.resolution.y) +
              "; points in world space)\n" + picker.text;
    }
    std::fwrite(out.data(), 1, out.size(), stdout);
    return ExitOk;
}

}  // namespace

void AddPickCommand(CLI::App &app, int *exitCode) {
    auto args = std::make_shared<PickArgs>();
    CLI::App *cmd = app.add_subcommand(
        "pick", "What the camera ray through the centre of pixel (X, Y) hits, and its bounces");
    cmd->add_option("scene", args->scene, "Scene file")->required();
    cmd->add_option("x", args->x, "Pixel column (0 = left)")->required();
    cmd->add_option("y", args->y, "Pixel row (0 = top)")->required();
    cmd->add_flag("--json", args->json, "Print one JSON object");
    cmd->add_option("--bounces", args->bounces,
                    "Specular bounces to follow (default 3; the scene's maxdepth limits them)")
        ->check(CLI::Range(0, 16));
    cmd->add_option("--res", args->res, "Resolution WxH (overrides the Film, as in render)");
    cmd->add_option("--precision", args->precision, "Arithmetic of the analytic intersectors")
        ->check(CLI::IsMember({"float", "double"}));
    cmd->add_flag("-q,--quiet", args->quiet, "No warnings");
    cmd->callback([args, exitCode] { *exitCode = RunGuarded([&] { return RunPick(*args); }); });
}

}  // namespace prism
