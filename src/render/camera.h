// pbrt-v3 perspective and orthographic cameras (left-handed camera space, +z forward, raster y
// down). fov applies to the shorter image axis through the default screen window.
#pragma once

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
    // pFilm: continuous raster position; uLens in [0,1)^2 (used only with a lens).
    Ray GenerateRay(Vec2f pFilm, Vec2f uLens) const;

  private:
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
