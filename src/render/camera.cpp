#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include "core/equal_area.h"
#include "render/lens_system.h"

namespace prism {

Camera::Camera(const CameraParams &p, const Transform &renderFromCamera, Vec2i res, double frame)
    : lens_(p.environment ? nullptr : p.lens),
      ortho_(p.orthographic && !p.environment && !p.lens),
      env_(p.environment),
      equalArea_(p.environment && p.equalArea),
      lensRadius_(p.lensRadius),
      focalDistance_(p.focalDistance),
      res_(res),
      renderFromCamera_(renderFromCamera) {
    bool custom = p.screenWindow[0] != 0 || p.screenWindow[1] != 0 || p.screenWindow[2] != 0 ||
                  p.screenWindow[3] != 0;
    if (custom) {
        sx0_ = p.screenWindow[0];
        sx1_ = p.screenWindow[1];
        sy0_ = p.screenWindow[2];
        sy1_ = p.screenWindow[3];
    } else if (frame > 1) {
        sx0_ = -frame;
        sx1_ = frame;
        sy0_ = -1;
        sy1_ = 1;
    } else {
        sx0_ = -1;
        sx1_ = 1;
        sy0_ = -1 / frame;
        sy1_ = 1 / frame;
    }
    tanHalf_ = std::tan(Radians(p.fovDeg) / 2);

    // Raster → screen is sx = sx0 + x ax, sy = sy1 + y ay.
    double ax = (sx1_ - sx0_) / res_.x, ay = -(sy1_ - sy0_) / res_.y;
    const Transform &m = renderFromCamera_;
    if (lens_) {
        // pbrt-v3 Film::GetPhysicalExtent: the diagonal split by the image's aspect ratio.
        const double aspect = double(res_.y) / res_.x;
        filmW_ = std::sqrt(p.filmDiagonal * p.filmDiagonal / (1 + aspect * aspect));
        filmH_ = aspect * filmW_;
    }
    if (env_ || lens_) {
        // Not affine in pFilm: GenerateRay computes every direction.
        oX_ = oY_ = dX_ = dY_ = d0_ = Vec3f(0, 0, 0);
        o0_ = Vec3f(m.Point(Vec3d(0, 0, 0)));
        lensRadius_ = 0;
    } else if (ortho_) {
        oX_ = Vec3f(m.Vector(Vec3d(ax, 0, 0)));
        oY_ = Vec3f(m.Vector(Vec3d(0, ay, 0)));
        o0_ = Vec3f(m.Point(Vec3d(sx0_, sy1_, 0)));
        dX_ = dY_ = Vec3f(0, 0, 0);
        d0_ = Vec3f(Normalize(m.Vector(Vec3d(0, 0, 1))));
    } else {
        oX_ = oY_ = Vec3f(0, 0, 0);
        o0_ = Vec3f(m.Point(Vec3d(0, 0, 0)));
        dX_ = Vec3f(m.Vector(Vec3d(ax * tanHalf_, 0, 0)));
        dY_ = Vec3f(m.Vector(Vec3d(0, ay * tanHalf_, 0)));
        d0_ = Vec3f(m.Vector(Vec3d(sx0_ * tanHalf_, sy1_ * tanHalf_, 1)));
    }
}

void Camera::SetMotion(const AnimatedTransform &renderFromCamera) {
    motion_ = std::make_shared<const AnimatedTransform>(renderFromCamera);
}

Vec3d Camera::EnvironmentDirection(Vec2f pFilm) const {
    if (equalArea_) {
        // pbrt-v4 SphericalCamera: a film position beyond an edge (a wide filter's sample)
        // continues across it as the octahedral map does, mirrored along that edge.
        double u = double(pFilm.x) / res_.x, v = double(pFilm.y) / res_.y;
        if (u < 0 || u > 1) {
            u = u < 0 ? -u : 2 - u;
            v = 1 - v;
        }
        if (v < 0 || v > 1) {
            v = v < 0 ? -v : 2 - v;
            u = 1 - u;
        }
        const Vec3d d = EqualAreaSquareToSphere({std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0)});
        return {d.x, d.z, d.y};  // the map's pole (z) is camera up (y)
    }
    // pbrt-v3 EnvironmentCamera: theta from camera +y down the rows, phi from +x toward +z
    // across the columns, over the full resolution (a crop window keeps its pixels' rays).
    const double theta = Pi * double(pFilm.y) / res_.y, phi = 2 * Pi * double(pFilm.x) / res_.x;
    const double sinTheta = std::sin(theta);
    return {sinTheta * std::cos(phi), std::cos(theta), sinTheta * std::sin(phi)};
}

Vec2d Camera::FilmPoint(Vec2f pFilm) const {
    // Raster (0, 0) is the film's (-w/2, -h/2); x is mirrored, as the lens inverts the image.
    const double fx = filmW_ * (double(pFilm.x) / res_.x - 0.5);
    const double fy = filmH_ * (double(pFilm.y) / res_.y - 0.5);
    return {-fx, fy};
}

Ray Camera::ToRender(const Vec3d &o, const Vec3d &d, float time) const {
    Ray ray;
    if (motion_) {
        const Transform m = motion_->Interpolate(double(time));
        ray.o = Vec3f(m.Point(o));
        ray.d = Vec3f(Normalize(m.Vector(d)));
    } else {
        ray.o = Vec3f(renderFromCamera_.Point(o));
        ray.d = Vec3f(Normalize(renderFromCamera_.Vector(d)));
    }
    ray.tMax = Infinity;
    ray.time = time;
    return ray;
}

float Camera::RayWeight(Vec2f pFilm, Vec2f uLens) const {
    if (!lens_) return 1;
    double w;
    lens_->GenerateRay(FilmPoint(pFilm), Vec2d(uLens.x, uLens.y), &w);
    return float(w);
}

Ray Camera::GenerateRay(Vec2f pFilm, Vec2f uLens, float time) const {
    if (env_) return ToRender(Vec3d(0, 0, 0), EnvironmentDirection(pFilm), time);
    if (lens_) {
        double w;
        const LensRay r = lens_->GenerateRay(FilmPoint(pFilm), Vec2d(uLens.x, uLens.y), &w);
        return ToRender(r.o, r.d, time);
    }
    if (lensRadius_ <= 0 && !motion_) {
        Ray ray;
        ray.o = o0_ + oX_ * pFilm.x + oY_ * pFilm.y;
        ray.d = Normalize(d0_ + dX_ * pFilm.x + dY_ * pFilm.y);
        ray.tMax = Infinity;
        ray.time = time;
        return ray;
    }
    // Raster → screen: raster row 0 is the top of the screen window (pbrt ScreenToRaster).
    double sx = sx0_ + (double(pFilm.x) / res_.x) * (sx1_ - sx0_);
    double sy = sy1_ - (double(pFilm.y) / res_.y) * (sy1_ - sy0_);
    Vec3d o, d;
    if (ortho_) {
        o = {sx, sy, 0};
        d = {0, 0, 1};
    } else {
        o = {0, 0, 0};
        d = Normalize(Vec3d(sx * tanHalf_, sy * tanHalf_, 1));
    }
    if (lensRadius_ > 0) {
        // Thin lens: concentric disk sample, focus on the plane z = focalDistance.
        double ux = 2.0 * uLens.x - 1, uy = 2.0 * uLens.y - 1, r, theta;
        if (ux == 0 && uy == 0) {
            r = 0;
            theta = 0;
        } else if (std::abs(ux) > std::abs(uy)) {
            r = ux;
            theta = (Pi / 4) * (uy / ux);
        } else {
            r = uy;
            theta = Pi / 2 - (Pi / 4) * (ux / uy);
        }
        Vec3d pLens(lensRadius_ * r * std::cos(theta), lensRadius_ * r * std::sin(theta), 0);
        double ft = focalDistance_ / d.z;
        Vec3d pFocus = o + d * ft;
        o = o + pLens;
        d = Normalize(pFocus - o);
    }
    return ToRender(o, d, time);
}

RayDifferential Camera::GenerateDifferential(const Ray &ray, Vec2f pFilm, Vec2f uLens, float time,
                                             float scale) const {
    const Ray rx = GenerateRay(pFilm + Vec2f(1, 0), uLens, time);
    const Ray ry = GenerateRay(pFilm + Vec2f(0, 1), uLens, time);
    RayDifferential rd{rx.o, ry.o, rx.d, ry.d};
    rd.Scale(ray.o, ray.d, scale);
    return rd;
}

}  // namespace prism
