#include "assembly/camera_film.h"

#include <algorithm>
#include <cmath>

#include "assembly/directive_params.h"
#include "assembly/film_sensor.h"
#include "assembly/lens_file.h"
#include "core/file_io.h"
#include "core/memory.h"
#include "core/pbrt_defaults.h"
#include "image/tonemap.h"
#include "render/aov.h"
#include "render/lens_system.h"
#include "render/renderer.h"

namespace prism {

// Film "image" (pbrt-v3's). Parameters:
//   xresolution, yresolution  integer  1280, 720  the image's size (--res wins)
//   cropwindow                float[4]  0 1 0 1  x0 x1 y0 y1 of the part rendered
//   filename                  string   ""        the output when -o is not given
//   scale                     float    1         multiplies every pixel
//   maxsampleluminance        float    infinity  samples brighter than this are scaled down
//   maxcomponentvalue         float    infinity  pbrt-v4: a sample whose largest component
//                                                exceeds this is scaled down to it
//   diagonal                  float    35        mm: read by the realistic camera only
//   exposure                  float    0         EV, in [-64, 64] (a Prism extension; --exposure
//                                                wins)
//   tonemap                   string   —         none | neutral | aces | filmic for 8-bit
//                                                outputs (a Prism extension; default none for pbrt,
//                                                neutral for OBJ, glTF and PLY; --tonemap wins)
//   aovs                      string   ""        the AOVs of an EXR output (a Prism extension;
//                                                --aov wins)
void BuildFilm(BuildContext &ctx) {
    const SceneDescription &desc = ctx.desc;
    const BuildSettings &settings = ctx.settings;
    RenderScene &scene = ctx.scene;
    Diagnostics &diag = ctx.diag;
    const ParamSet &film = desc.film.params;
    int xres = film.GetInt("xresolution", PbrtDefaultXResolution);
    int yres = film.GetInt("yresolution", PbrtDefaultYResolution);
    // The file's values are checked even when settings replace them: they are bad input.
    const int maxRes = MaxImageResolution;
    if (xres <= 0 || yres <= 0 || xres > maxRes || yres > maxRes) {
        const Param *p = film.Find(xres <= 0 || xres > maxRes ? "xresolution" : "yresolution");
        throw SceneError(p ? p->loc : desc.film.loc,
                         "image resolution " + std::to_string(xres) + "x" + std::to_string(yres) +
                             " is out of range (1 to " + std::to_string(maxRes) + " per axis)");
    }
    if (settings.resolution.x > 0) {
        xres = settings.resolution.x;
        yres = settings.resolution.y;
        // The caller checks its own values (and names their source); this is the backstop.
        if (xres > maxRes || yres > maxRes)
            throw SceneError("resolution " + std::to_string(xres) + "x" + std::to_string(yres) +
                             " is out of range (1 to " + std::to_string(maxRes) + " per axis)");
    }
    scene.resolution = {xres, yres};
    std::array<float, 4> crop{0, 1, 0, 1};
    std::vector<float> cw = film.GetFloats("cropwindow");
    if (cw.size() == 4) std::copy(cw.begin(), cw.end(), crop.begin());
    if (settings.crop) crop = *settings.crop;
    crop = {
        Clamp(std::min(crop[0], crop[1]), 0.f, 1.f), Clamp(std::max(crop[0], crop[1]), 0.f, 1.f),
        Clamp(std::min(crop[2], crop[3]), 0.f, 1.f), Clamp(std::max(crop[2], crop[3]), 0.f, 1.f)};
    Bounds2i pb;
    pb.pMin = {int(std::ceil(xres * crop[0])), int(std::ceil(yres * crop[2]))};
    pb.pMax = {int(std::ceil(xres * crop[1])), int(std::ceil(yres * crop[3]))};
    if (pb.pMax.x <= pb.pMin.x || pb.pMax.y <= pb.pMin.y)
        throw SceneError(desc.film.loc, "the crop window covers no pixels");
    scene.pixelBounds = pb;
    scene.outputFilename = film.GetString("filename", "");
    scene.filmScale = film.GetFloat("scale", 1.f);
    scene.maxSampleLuminance = film.GetFloat("maxsampleluminance", Infinity);
    scene.maxComponentValue = film.GetFloat("maxcomponentvalue", Infinity);
    for (const char *clamp : {"maxsampleluminance", "maxcomponentvalue"})
        if (const Param *p = film.Find(clamp); p && !(film.GetFloat(clamp, 1) > 0))
            throw SceneError(p->loc, std::string("film \"") + clamp + "\" must be positive");
    // Prism extensions (docs/FORMAT.md): exposure in EV and the tone map of 8-bit outputs;
    // the command line's --exposure and --tonemap replace them.
    scene.filmExposure = film.GetFloat("exposure", 0.f);
    if (!std::isfinite(scene.filmExposure) || std::abs(scene.filmExposure) > 64) {
        const Param *p = film.Find("exposure");
        throw SceneError(p ? p->loc : desc.film.loc, "film \"exposure\" must lie in [-64, 64]");
    }
    // The tone map of 8-bit outputs: the Film's, else none (clamp, as pbrt-v3) for pbrt
    // scenes and neutral (Khronos PBR Neutral) for OBJ, glTF and PLY.
    scene.filmToneMap = desc.format == "pbrt" ? ToneMap::None : ToneMap::Neutral;
    if (const Param *p = film.Find("tonemap")) {
        ToneMap op;
        std::string name = film.GetString("tonemap", "");
        if (!ParseToneMap(name, &op))
            throw SceneError(p->loc, "unknown film \"tonemap\" " + Quote(name) +
                                         " (expected none, neutral, aces or filmic)");
        scene.filmToneMap = op;
    }
    // OBJ, glTF and PLY models lit by their own emitters (not the studio rig), whose units are
    // arbitrary, are exposed automatically in 8-bit outputs. Decided here with the tone map, so
    // that writing an image needs no SceneDescription.
    scene.autoExposure8Bit = desc.format != "pbrt" && !desc.studioRig;
    if (const Param *p = film.Find("aovs")) {
        std::vector<Aov> aovs;
        std::string error;
        scene.filmAovs = film.GetString("aovs", "");
        if (!ParseAovList(scene.filmAovs, &aovs, &error))
            throw SceneError(p->loc, "film \"aovs\": " + error);
    }
    // The realistic camera reads the film's physical size (BuildCamera); the others do not.
    if (desc.camera.type != "realistic")
        WarnIgnored(film, {"diagonal"}, diag, "film",
                    "the film's physical size is not simulated (only the realistic camera's)");
    BuildFilmSensor(ctx);  // pbrt-v4's iso and white balance
    film.ReportUnused(diag, "film");
}

void ChargeFilmMemory(BuildContext &ctx) {
    const Bounds2i &pb = ctx.scene.pixelBounds;
    const Vec2i res = ctx.scene.resolution;
    uint64_t bytes =
        EstimateFilmBytes(uint64_t(pb.pMax.x - pb.pMin.x), uint64_t(pb.pMax.y - pb.pMin.y),
                          ctx.scene.filter.radiusX, ctx.scene.filter.radiusY, RenderTileSize);
    // A resolution from the settings has no location in the file.
    const Param *p = ctx.desc.film.params.Find("xresolution");
    FileLoc loc = ctx.settings.resolution.x > 0 ? FileLoc{} : p ? p->loc : ctx.desc.film.loc;
    ctx.budget.Charge(bytes, "image " + std::to_string(res.x) + "x" + std::to_string(res.y), loc);
}

namespace {

// The perspective and orthographic cameras' fov, screen window and thin lens.
// Camera "perspective", "orthographic" (pbrt-v3's). Parameters:
//   fov            float     90       perspective: the field of view across the image's
//                                     shorter side, degrees
//   halffov        float     —        perspective: half of fov (pbrt-v3's alternative)
//   screenwindow   float[4]  —        x0 x1 y0 y1 of the image plane (default: the aspect
//                                     ratio's, [-1, 1] across the shorter side)
//   lensradius     float     0        the thin lens's radius (depth of field when > 0)
//   focaldistance  float     1e6      the distance in focus
// Every camera also reads shutteropen, shutterclose and frameaspectratio (BuildCamera).
void ReadProjection(const CameraDesc &cd, const BuildSettings &settings, CameraParams *params) {
    const ParamSet &cp = cd.params;
    params->fovDeg = cp.GetFloat("fov", PbrtDefaultFovDeg);
    float halffov = cp.GetFloat("halffov", -1.f);
    if (halffov > 0) params->fovDeg = 2 * halffov;
    if (settings.fovDeg > 0) params->fovDeg = settings.fovDeg;
    if (!(params->fovDeg > 0 && params->fovDeg < 180)) {
        const Param *p = cp.Find("fov");
        throw SceneError(p ? p->loc : cd.loc, "camera fov must be between 0 and 180 degrees");
    }
    std::vector<float> sw = cp.GetFloats("screenwindow");
    if (sw.size() == 4)
        for (int i = 0; i < 4; ++i) params->screenWindow[i] = sw[size_t(i)];
    params->lensRadius = cp.GetFloat("lensradius", 0.f);
    params->focalDistance = cp.GetFloat("focaldistance", 1e6f);
}

// Camera "realistic" (pbrt-v3 RealisticCamera). Parameters:
//   lensfile          string  ""    the lens description file (assembly/lens_file.h),
//                                   relative to the scene; required
//   aperturediameter  float   1     the aperture stop's diameter, mm (clamped, with a
//                                   warning, to the file's)
//   focusdistance     float   10    the distance from the film that is in focus, m
//   simpleweighting   bool    true  weights cos^4 times the exit pupil's area over the
//                                   centre's (else times the shutter time over the rear
//                                   distance squared: pbrt-v3's physical weighting)
//   shutteropen, shutterclose  float  0, 1  the shutter interval (every camera's; the
//                                           physical weighting's shutter time)
//   diagonal                   float  35    the Film's (not the camera's): its diagonal, mm
std::shared_ptr<const LensSystem> ReadLens(BuildContext &ctx, CameraParams *params) {
    const CameraDesc &cd = ctx.desc.camera;
    const ParamSet &cp = cd.params;
    auto loc = [&](const char *name) {
        const Param *p = cp.Find(name);
        return p ? p->loc : cd.loc;
    };
    const std::string file = cp.GetString("lensfile", "");
    if (file.empty()) throw SceneError(cd.loc, "the realistic camera needs a \"lensfile\"");
    const std::string path = ResolveScenePath(ctx.desc, file);
    CheckReadConfinement(path, loc("lensfile"), "lens file", file);
    const std::string text =
        ReadFileOrThrow(path, loc("lensfile"), ctx.budget, "lens file " + Quote(file));
    std::vector<LensInterface> lens = ParseLensFile(text, path);

    const float aperture = cp.GetFloat("aperturediameter", 1.f);
    if (!(aperture > 0 && aperture < 1e5f))
        throw SceneError(loc("aperturediameter"), "camera \"aperturediameter\" must be positive");
    bool stop = false;
    for (LensInterface &e : lens) {
        if (e.radius != 0) continue;
        stop = true;
        const double r = 0.5e-3 * aperture;
        if (r > e.apertureRadius)
            ctx.diag.Warn(loc("aperturediameter"), "aperture diameter " + std::to_string(aperture) +
                                                       " mm is larger than the lens's stop (" +
                                                       std::to_string(e.apertureRadius * 2e3) +
                                                       " mm); using the stop's");
        else
            e.apertureRadius = r;
    }
    if (!stop && cp.Find("aperturediameter"))
        ctx.diag.Warn(loc("aperturediameter"),
                      "the lens file has no aperture stop (a row of radius 0): "
                      "\"aperturediameter\" has no effect");
    const float focus = cp.GetFloat("focusdistance", 10.f);
    if (!(focus > 0 && focus < 1e9f))
        throw SceneError(loc("focusdistance"), "camera \"focusdistance\" must be positive");
    const bool simple = cp.GetBool("simpleweighting", true);
    const ParamSet &film = ctx.desc.film.params;
    const float diagonal = film.GetFloat("diagonal", 35.f);
    if (!(diagonal > 0 && diagonal < 1e5f)) {
        const Param *p = film.Find("diagonal");
        throw SceneError(p ? p->loc : ctx.desc.film.loc, "film \"diagonal\" must be positive");
    }
    params->filmDiagonal = diagonal * 1e-3;
    // Physical weighting integrates over the shutter (BuildCamera checks and orders the times).
    const double shutter =
        std::abs(double(cp.GetFloat("shutterclose", 1.f)) - cp.GetFloat("shutteropen", 0.f));
    try {
        return std::make_shared<const LensSystem>(std::move(lens), double(focus),
                                                  params->filmDiagonal, simple, shutter);
    } catch (const std::invalid_argument &e) {
        throw SceneError(loc("focusdistance"), std::string("realistic camera: ") + e.what());
    }
}

}  // namespace

// Camera "environment" (pbrt-v3's) and "spherical" (pbrt-v4's), and the parameters every
// camera reads. Parameters:
//   mapping                    string  equalarea  spherical: equalarea (a square film
//                                                 through the equal-area map) or
//                                                 equirectangular (pbrt-v3's "environment")
//   shutteropen, shutterclose  float  0, 1   the interval the image integrates over (a reversed
//                                            pair is swapped with a warning)
//   frameaspectratio           float  —      the film's width over its height (default: the
//                                            resolution's)
//   screenwindow               float[4]  —   environment and realistic: read and ignored, as in
//                                            pbrt-v3
void BuildCamera(BuildContext &ctx) {
    const SceneDescription &desc = ctx.desc;
    const BuildSettings &settings = ctx.settings;
    RenderScene &scene = ctx.scene;
    Diagnostics &diag = ctx.diag;
    const CameraDesc &cd = desc.camera;
    const ParamSet &cp = cd.params;
    CameraParams params;
    std::string type = cd.specified ? cd.type : "perspective";
    if (type == "orthographic") {
        params.orthographic = true;
    } else if (type == "environment") {
        params.environment = true;
    } else if (type == "spherical") {
        params.environment = true;
        const std::string mapping = cp.GetString("mapping", "equalarea");
        const Param *m = cp.Find("mapping");
        if (mapping == "equalarea") {
            params.equalArea = true;
            if (scene.resolution.x != scene.resolution.y)
                diag.Warn(m ? m->loc : cd.loc,
                          "the spherical camera's \"equalarea\" mapping fills a square film; "
                          "this " +
                              std::to_string(scene.resolution.x) + "x" +
                              std::to_string(scene.resolution.y) + " one stretches it");
        } else if (mapping != "equirectangular") {
            throw SceneError(m ? m->loc : cd.loc,
                             "spherical camera mapping " + Quote(mapping) +
                                 " is not one of \"equalarea\", \"equirectangular\"");
        }
    } else if (type == "realistic") {
        params.lens = ReadLens(ctx, &params);
    } else if (type != "perspective") {
        diag.Warn(cd.loc, "camera " + Quote(type) + " is not supported; using perspective");
    }
    if (params.environment || params.lens) {
        // pbrt-v3's environment and realistic cameras read their screen window and ignore
        // it, and read no fov or thin lens (those are reported unused, as pbrt-v3 does).
        cp.GetFloats("screenwindow");
    } else {
        ReadProjection(cd, settings, &params);
    }
    scene.features.lens = params.lensRadius > 0 || params.lens;
    if (scene.features.lens) {
        const Param *lr = cp.Find(params.lens ? "lensfile" : "lensradius");
        scene.features.effects.Enable(
            Effect::DepthOfField,
            "Camera " + Quote(type) + (params.lens ? " \"lensfile\"" : " \"lensradius\""),
            lr ? lr->loc : cd.loc);
    }
    const Vec2i res = scene.resolution;
    double frame = cp.GetFloat("frameaspectratio", float(double(res.x) / res.y));
    // pbrt-v3: the shutter is open from "shutteropen" to "shutterclose" (default 0 1); a
    // reversed pair is swapped with a warning.
    double open = cp.GetFloat("shutteropen", 0.f), close = cp.GetFloat("shutterclose", 1.f);
    if (!std::isfinite(open) || !std::isfinite(close)) {
        const Param *p = cp.Find("shutteropen");
        throw SceneError(p ? p->loc : cd.loc, "camera shutter times must be finite");
    }
    if (close < open) {
        const Param *p = cp.Find("shutterclose");
        diag.Warn(p ? p->loc : cd.loc, "camera shutterclose " + std::to_string(close) +
                                           " is before shutteropen " + std::to_string(open) +
                                           "; swapping them (as pbrt-v3)");
        std::swap(open, close);
    }
    ctx.shutterOpen = open;
    ctx.shutterClose = close;
    cp.ReportUnused(diag, "camera");

    Transform worldFromCamera = cd.cameraFromWorld.Inverse();
    std::optional<TransformMotion> motion;  // a moving camera: worldFromCamera at the end
    if (cd.motion && !settings.worldFromCamera)
        motion = TransformMotion{cd.motion->end.Inverse(), cd.motion->startTime, cd.motion->endTime,
                                 cd.motion->loc};
    if (settings.worldFromCamera) {
        worldFromCamera = *settings.worldFromCamera;
        // --lookat is pbrt's LookAt, whose camera frame is left-handed as pbrt worlds are.
        // OBJ, glTF and PLY worlds are right-handed: flip camera x, as the default camera
        // does (scene/load_scene.cpp), or world +x would show on the left looking down -z.
        if (ctx.desc.format != "pbrt") worldFromCamera = worldFromCamera * Scale(-1, 1, 1);
    }
    // Render in camera-centred world space (pbrt-v4 "cameraworld"): far-away scenes keep
    // full float precision near the viewer (the viewer at the shutter's opening).
    Transform renderFromCamera;
    std::optional<AnimatedTransform> moving =
        ShutterMotion(ctx, nullptr, worldFromCamera, motion, cd.loc, &renderFromCamera);
    worldFromCamera = renderFromCamera;  // at the shutter's opening (still world space here)
    Vec3d eye = worldFromCamera.Point(Vec3d(0, 0, 0));
    scene.renderFromWorld = settings.cameraRelative ? Translate(-eye) : Transform();
    scene.camera = std::make_unique<Camera>(params, scene.renderFromWorld * worldFromCamera,
                                            scene.resolution, frame);
    if (moving) {
        // The same motion in render space (its keyframes translated like the world).
        scene.camera->SetMotion(
            AnimatedTransform(scene.renderFromWorld * moving->Start(), moving->StartTime(),
                              scene.renderFromWorld * moving->End(), moving->EndTime()));
    }
    // Every ray handed to Embree must be finite and within its range (geometry/accel.h
    // TraceableRay): the rays through the film's corners and centre, from the lens's corners
    // and centre, at the shutter's open, middle and close bound what the camera makes (its
    // rays are affine in the film position and lens sample). Finite but huge camera values
    // (a lens radius of 1e30, Scale 1e38 before the Camera, a +-3e38 screen window) fail here.
    const Vec2f film(float(scene.resolution.x), float(scene.resolution.y));
    for (Vec2f f : {Vec2f(0, 0), Vec2f(film.x, 0), Vec2f(0, film.y), film, film * 0.5f})
        for (Vec2f u : {Vec2f(0, 0), Vec2f(1, 0), Vec2f(0, 1), Vec2f(1, 1), Vec2f(0.5f, 0.5f)})
            for (float time : {0.f, 0.5f, 1.f}) {
                const Ray r = scene.camera->GenerateRay(f, u, time);
                if (!TraceableRay(r) || !(LengthSquared(r.d) > 0))
                    throw SceneError(cd.loc.Valid() ? cd.loc : desc.film.loc,
                                     "the camera makes rays that cannot be traced (not finite, "
                                     "or beyond 1e18 in render space): check its transform, "
                                     "lensradius, focaldistance and screenwindow");
            }
}

}  // namespace prism
