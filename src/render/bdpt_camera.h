// The camera as the light subpaths of the bidirectional integrator see it (pbrt-v3's
// PerspectiveCamera::We, Pdf_We and Sample_Wi): the importance a ray leaving the lens carries
// toward the crop window's pixels, the densities with which camera rays are drawn, and a point
// on the lens sampled toward a scene point (light tracing, the t = 1 strategies). The
// importance is normalized over the crop window, so its pixels' splats sum to the measurement
// a camera ray through them estimates (pbrt-v3 normalizes over the full film, which darkens
// light tracing in a cropped render).
#pragma once

#include "core/color.h"
#include "core/transform.h"
#include "image/bounds2.h"
#include "render/camera.h"

namespace prism {

class CameraImportance {
  public:
    CameraImportance() = default;
    // Perspective cameras only (Supported()); the transform at shutter open.
    CameraImportance(const Camera &camera, const Bounds2i &crop);
    bool Supported() const { return supported_; }

    // The importance of the ray from lens point p (render space) in unit direction w, and the
    // continuous raster position it reaches; 0 outside the crop window or behind the camera.
    float We(const Vec3f &p, const Vec3f &w, Vec2f *raster) const;
    // The densities of camera rays: per unit lens area, and per solid angle of w.
    void Pdf(const Vec3f &w, float *pdfPos, float *pdfDir) const;

    // A lens point seen from ref (light tracing). *wi: unit direction from ref to the lens
    // point, *pdf: its solid-angle density at ref, *we: the importance toward ref.
    struct Sample {
        Vec3f pLens, wi, nLens;
        float pdf = 0, we = 0, dist = 0;
        Vec2f raster;
    };
    bool SampleWi(const Vec3f &ref, Vec2f u, Sample *s) const;

  private:
    bool supported_ = false;
    Camera::Projection proj_{};
    Transform renderFromCamera_, cameraFromRender_;
    Vec3f forward_;
    Bounds2i crop_;
    double area_ = 1;      // the crop window's area on the plane z = 1 (camera space)
    double lensArea_ = 1;  // pi r^2, or 1 for a pinhole
};

}  // namespace prism
