// pbrt-v3 perspective and orthographic cameras (left-handed camera space, +z forward, raster y
// down). fov applies to the shorter image axis through the default screen window.
#pragma once

#include <memory>

#include "core/animated_transform.h"
#include "core/pbrt_defaults.h"
#include "core/transform.h"
#include "geometry/ray.h"

namespace prism {

struct CameraParams {
    bool orthographic = false;
    double fovDeg = PbrtDefaultFovDeg;
    double screenWindow[4] = {0, 0, 0, 0};  // x0 x1 y0 y1; all zero → pbrt default
    double lensRadius = 0, focalDistance = 1e6;
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
    };
    Projection GetProjection() const {
        return {ortho_, sx0_, sx1_, sy0_, sy1_, tanHalf_, lensRadius_, focalDistance_, res_};
    }
    bool Moves() const { return motion_ != nullptr; }

  private:
    std::shared_ptr<const AnimatedTransform> motion_;
    bool ortho_;
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
