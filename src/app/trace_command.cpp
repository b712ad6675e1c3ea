// `prism trace SCENE --rays FILE [-o OUT] [--occluded]`: world-space ray queries for users who
// validate intersectors. One output line per ray, %.9g:
//   hit t px py pz nx ny nz shape prim   |   miss      (or 1/0 with --occluded)
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "app/commands.h"
#include "app/common.h"
#include "assembly/build_scene.h"
#include "core/output_file.h"
#include "scene/load_scene.h"

namespace prism {

namespace {

struct TraceArgs {
    std::string scene, rays, output, precision = "double", maxMemory;
    bool occluded = false, quiet = false;
};

// Parses "ox oy oz dx dy dz [tmin tmax]"; '#' starts a comment. Returns false for blank lines.
bool ParseRayLine(const std::string &line, const std::string &file, int lineNo, Ray *ray) {
    std::string text = line.substr(0, line.find('#'));
    std::istringstream in(text);
    std::vector<double> v;
    std::string tok;
    while (in >> tok) {
        try {
            size_t used = 0;
            double x = std::stod(tok, &used);
            if (used != tok.size()) throw std::invalid_argument(tok);
            v.push_back(x);
        } catch (const std::exception &) {
            throw SceneError(FileLoc{file, lineNo, 1}, "invalid number \"" + tok + "\" in ray");
        }
    }
    if (v.empty()) return false;
    if (v.size() != 6 && v.size() != 8)
        throw SceneError(FileLoc{file, lineNo, 1},
                         "a ray needs 6 or 8 numbers (ox oy oz dx dy dz [tmin tmax]), got " +
                             std::to_string(v.size()));
    ray->o = Vec3f(float(v[0]), float(v[1]), float(v[2]));
    ray->d = Vec3f(float(v[3]), float(v[4]), float(v[5]));
    ray->tMin = v.size() == 8 ? float(v[6]) : 0.f;
    ray->tMax = v.size() == 8 ? float(v[7]) : Infinity;
    if (LengthSquared(ray->d) == 0)
        throw SceneError(FileLoc{file, lineNo, 1}, "ray direction is zero");
    if (ray->o.HasNaN() || ray->d.HasNaN() || std::isnan(ray->tMin) || std::isnan(ray->tMax) ||
        !(ray->tMin >= 0) || ray->tMin > ray->tMax)
        throw SceneError(FileLoc{file, lineNo, 1},
                         "invalid ray (NaN, negative tmin or tmin > tmax)");
    return true;
}

int RunTrace(const TraceArgs &a) {
    Diagnostics diag(!a.quiet);
    MemoryBudget budget(ParseMaxMemory(a.maxMemory));  // scene, meshes and BVH together
    LoadOptions loadOpts;
    loadOpts.budget = &budget;
    SceneDescription desc = LoadScene(a.scene, diag, loadOpts);
    BuildSettings opts;
    opts.budget = &budget;
    opts.precision = ParsePrecision(a.precision);
    opts.cameraRelative = false;  // rays are given in world space
    RenderScene scene = BuildRenderScene(desc, opts, diag);

    std::ifstream in(a.rays);
    if (!in) throw SceneError(FileLoc{a.rays, 0, 0}, "cannot open ray file \"" + a.rays + "\"");
    std::string out;
    std::string line;
    int lineNo = 0;
    char buf[512];
    while (std::getline(in, line)) {
        ++lineNo;
        Ray ray;
        if (!ParseRayLine(line, a.rays, lineNo, &ray)) continue;
        if (a.occluded) {
            out += scene.accel->Occluded(ray) ? "1\n" : "0\n";
            continue;
        }
        RawHit hit;
        if (!scene.accel->IntersectRaw(ray, &hit)) {
            out += "miss\n";
            continue;
        }
        SurfaceInteraction si = scene.accel->Interaction(ray, hit);
        // The geometric normal as pbrt orients it: not turned toward the ray, not bent toward
        // shading normals.
        Vec3f n = si.n;
        if (const TriangleMesh *mesh = scene.accel->Mesh(hit.shape))
            n = mesh->GeometricNormal(size_t(hit.prim));
        // A CSG hit names the operand's Shape directive.
        const ShapeInfo &top = scene.shapes[size_t(hit.shape)];
        int directive = top.type == "csg" ? scene.Info(si).directiveIndex : top.directiveIndex;
        std::snprintf(buf, sizeof(buf), "hit %.9g %.9g %.9g %.9g %.9g %.9g %.9g %d %d\n",
                      // + 0.0 prints -0 as 0
                      double(hit.t) + 0.0, double(si.p.x) + 0.0, double(si.p.y) + 0.0,
                      double(si.p.z) + 0.0, double(n.x) + 0.0, double(n.y) + 0.0, double(n.z) + 0.0,
                      directive, hit.prim);
        out += buf;
    }
    if (a.output.empty())
        std::fwrite(out.data(), 1, out.size(), stdout);
    else
        WriteFileAtomically(a.output, out);
    return ExitOk;
}

}  // namespace

void AddTraceCommand(CLI::App &app, int *exitCode) {
    auto args = std::make_shared<TraceArgs>();
    CLI::App *cmd =
        app.add_subcommand("trace", "Trace world-space rays from a file against a scene");
    cmd->add_option("scene", args->scene, "Scene file")->required();
    cmd->add_option("--rays", args->rays, "Ray file: 'ox oy oz dx dy dz [tmin tmax]' per line")
        ->required();
    cmd->add_option("-o,--output", args->output, "Output file (default: standard output)");
    cmd->add_flag("--occluded", args->occluded, "Occlusion query: print 1 or 0 per ray");
    cmd->add_option("--max-memory", args->maxMemory,
                    "Memory budget, e.g. 512M or 8G (default: 75% of RAM)");
    cmd->add_option("--precision", args->precision, "Arithmetic of the analytic intersectors")
        ->check(CLI::IsMember({"float", "double"}));
    cmd->add_flag("-q,--quiet", args->quiet, "No warnings");
    cmd->callback([args, exitCode] { *exitCode = RunGuarded([&] { return RunTrace(*args); }); });
}

}  // namespace prism
