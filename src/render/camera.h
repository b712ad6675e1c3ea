// pbrt-v3 perspective, orthographic, environment and realistic cameras and pbrt-v4's spherical
// one (left-handed camera
// space, +z forward, raster y down). fov applies to the shorter image axis through the default
// screen window; the environment camera sees the whole sphere of directions in
// latitude-longitude; the realistic camera traces rays from its film through a lens system
// (render/lens_system.h).
#pragma once

#include <memory>

#include "core/animated_transform.h"
#include "core/pbrt_defaults.h"
#include "core/transform.h"
#include "geometry/ray.h"

namespace prism {

class LensSystem;

struct CameraParams {
    bool orthographic = false;
    // pbrt-v3's "environment" camera: raster (x, y) of a W x H film looks along camera-space
    // (sin t cos p, cos t, sin t sin p), t = pi y / H from +y, p = 2 pi x / W from +x toward
    // +z; fov, screen window and lens are not read.
    bool environment = false;
    // pbrt-v4's "spherical" camera with its default "equalarea" mapping: raster (x, y) / (W, H)
    // through core/equal_area.h's square-to-sphere map, its pole turned to camera +y (the
    // "equirectangular" mapping is the environment camera above).
    bool equalArea = false;
    double fovDeg = PbrtDefaultFovDeg;
    double screenWindow[4] = {0, 0, 0, 0};  // x0 x1 y0 y1; all zero → pbrt default
    double lensRadius = 0, focalDistance = 1e6;
    // pbrt-v3's "realistic" camera: rays from a film of this diagonal (metres) through the
    // lens, which replaces fov, screen window and thin lens.
    std::shared_ptr<const LensSystem> lens;
    double filmDiagonal = 0.035;
};

class Camera {
  public:
    // renderFromCamera maps camera space to the render space (world translated to the eye).
    Camera(const CameraParams &params, const Transform &renderFromCamera, Vec2i fullResolution,
           double frameAspectRatio);
    // pFilm: continuous raster position; uLens in [0,1)^2 (used only with a lens); time: the
    // ray's time as a fraction of the shutter (Ray::time; it moves only a moving camera).
    Ray GenerateRay(Vec2f pFilm, Vec2f uLens, float time = 0) const;
    // pbrt-v3 GenerateRayDifferential for `ray` = GenerateRay(pFilm, uLens, time): the rays
    // through pFilm + (1, 0) and pFilm + (0, 1) with the same lens sample and time (for every
    // camera type this is what pbrt-v3 computes), scaled toward `ray` by `scale` (pbrt-v3
    // ScaleDifferentials with max(1/8, 1/sqrt(spp))).
    RayDifferential GenerateDifferential(const Ray &ray, Vec2f pFilm, Vec2f uLens, float time,
                                         float scale) const;
    // The radiance weight of the ray GenerateRay(pFilm, uLens, ...) makes: 1 but for the
    // realistic camera (pbrt-v3's ray weight, 0 where the lens blocks the ray: the ray made
    // then is one that contributes nothing).
    bool HasRayWeights() const { return lens_ != nullptr; }
    float RayWeight(Vec2f pFilm, Vec2f uLens) const;
    // Motion blur: renderFromCamera over the shutter (times as fractions of it; its value at 0
    // the transform the camera was made with).
    void SetMotion(const AnimatedTransform &renderFromCamera);
    // Camera space to render space at time 0 (the AOVs' depth axis, render/aov.h).
    const Transform &RenderFromCamera() const { return renderFromCamera_; }
    // The projection, for light tracing's importance (render/bdpt_camera.h): raster (x, y)
    // looks along camera-space (sx tanHalf, sy tanHalf, 1), sx = sx0 + x/res.x (sx1 - sx0),
    // sy = sy1 - y/res.y (sy1 - sy0); a thin lens of lensRadius focuses at focalDistance.
    struct Projection {
        bool orthographic;
        double sx0, sx1, sy0, sy1, tanHalf, lensRadius, focalDistance;
        Vec2i resolution;
        bool environment = false;  // not a projection: the lat-long camera (no importance)
        bool realistic = false;    // nor the lens system
    };
    Projection GetProjection() const {
        Projection p{ortho_, sx0_, sx1_, sy0_, sy1_, tanHalf_, lensRadius_, focalDistance_, res_};
        p.environment = env_;
        p.realistic = lens_ != nullptr;
        return p;
    }
    // The environment (lat-long) or equal-area camera's camera-space direction of raster
    // position pFilm.
    Vec3d EnvironmentDirection(Vec2f pFilm) const;
    bool Moves() const { return motion_ != nullptr; }

  private:
    std::shared_ptr<const AnimatedTransform> motion_;
    // The realistic camera's lens and the camera-space film point of raster position pFilm.
    Vec2d FilmPoint(Vec2f pFilm) const;
    // Camera space to render space at `time` (the motion's, else the fixed transform).
    Ray ToRender(const Vec3d &o, const Vec3d &d, float time) const;
    std::shared_ptr<const LensSystem> lens_;
    double filmW_ = 0, filmH_ = 0;  // the film's physical size (realistic camera)
    bool ortho_, env_, equalArea_;
    double sx0_, sx1_, sy0_, sy1_, tanHalf_;
    double lensRadius_, focalDistance_;
    Vec2i res_;
    Transform renderFromCamera_;
    // Without a lens, the ray is affine in pFilm: render-space origin = oX x + oY y + o0 and
    // (unnormalized) direction = dX x + dY y + d0, folded from renderFromCamera in double and
    // evaluated per ray in float.
    Vec3f oX_, oY_, o0_, dX_, dY_, d0_;
};

}  // namespace prism
