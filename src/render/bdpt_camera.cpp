#include "render/bdpt_camera.h"

#include <cmath>

#include "render/light.h"

namespace prism {

CameraImportance::CameraImportance(const Camera &camera, const Bounds2i &crop)
    : proj_(camera.GetProjection()),
      renderFromCamera_(camera.RenderFromCamera()),
      cameraFromRender_(camera.RenderFromCamera().Inverse()),
      crop_(crop) {
    supported_ = !proj_.orthographic && !proj_.environment && !proj_.realistic && !crop.Empty();
    forward_ = Vec3f(Normalize(renderFromCamera_.Vector(Vec3d(0, 0, 1))));
    const Vec2i res = proj_.resolution;
    // The full screen window's area on z = 1, scaled to the crop window's share of the pixels.
    const double full =
        std::abs((proj_.sx1 - proj_.sx0) * (proj_.sy1 - proj_.sy0)) * proj_.tanHalf * proj_.tanHalf;
    area_ = full * double(crop.Area()) / (double(res.x) * double(res.y));
    lensArea_ = proj_.lensRadius > 0 ? Pi * proj_.lensRadius * proj_.lensRadius : 1.0;
}

float CameraImportance::We(const Vec3f &p, const Vec3f &w, Vec2f *raster) const {
    if (!supported_) return 0;
    const Vec3d d = Normalize(cameraFromRender_.Vector(Vec3d(w)));
    const double cosTheta = d.z;
    if (!(cosTheta > 0)) return 0;
    // The point the ray focuses on, seen through the lens centre (a pinhole: the ray itself).
    Vec3d q = d / d.z;
    if (proj_.lensRadius > 0) {
        const Vec3d o = cameraFromRender_.Point(Vec3d(p));
        q = o + d * (proj_.focalDistance / d.z);
        if (!(q.z > 0)) return 0;
        q = q / q.z;
    }
    const double sx = q.x / proj_.tanHalf, sy = q.y / proj_.tanHalf;
    const Vec2i res = proj_.resolution;
    const double x = (sx - proj_.sx0) / (proj_.sx1 - proj_.sx0) * res.x;
    const double y = (proj_.sy1 - sy) / (proj_.sy1 - proj_.sy0) * res.y;
    if (!(x >= crop_.pMin.x && x < crop_.pMax.x && y >= crop_.pMin.y && y < crop_.pMax.y)) return 0;
    *raster = Vec2f(float(x), float(y));
    const double cos2 = cosTheta * cosTheta;
    return float(1 / (area_ * lensArea_ * cos2 * cos2));
}

void CameraImportance::Pdf(const Vec3f &w, float *pdfPos, float *pdfDir) const {
    const double cosTheta = Dot(Vec3d(w), Vec3d(forward_));
    if (!supported_ || !(cosTheta > 0)) {
        *pdfPos = *pdfDir = 0;
        return;
    }
    *pdfPos = float(1 / lensArea_);
    *pdfDir = float(1 / (area_ * cosTheta * cosTheta * cosTheta));
}

bool CameraImportance::SampleWi(const Vec3f &ref, Vec2f u, Sample *s) const {
    if (!supported_) return false;
    Vec3d pc(0, 0, 0);
    if (proj_.lensRadius > 0) {
        const Vec2f d = ConcentricDisk(u);
        pc = Vec3d(proj_.lensRadius * d.x, proj_.lensRadius * d.y, 0);
    }
    s->pLens = Vec3f(renderFromCamera_.Point(pc));
    s->nLens = forward_;
    Vec3f wi = s->pLens - ref;
    const float dist = Length(wi);
    if (!(dist > 0)) return false;
    wi = wi / dist;
    const float cosLens = std::abs(Dot(forward_, wi));
    if (!(cosLens > 0)) return false;
    s->wi = wi;
    s->dist = dist;
    s->pdf = float(double(dist) * dist / (cosLens * lensArea_));
    s->we = We(s->pLens, -wi, &s->raster);
    return s->we > 0 && std::isfinite(s->pdf);
}

}  // namespace prism
