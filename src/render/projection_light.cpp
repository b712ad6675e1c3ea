#include "render/projection_light.h"

#include <cmath>

#include "image/image.h"
#include "render/goniometric_light.h"

namespace prism {

namespace {

// The solid angle of [0, x] x [0, y] on the plane z = 1 seen from the origin (signed), so a
// rectangle's is the alternating sum over its corners.
double CornerSolidAngle(double x, double y) {
    return std::atan(x * y / std::sqrt(1 + x * x + y * y));
}

double RectSolidAngle(double x0, double x1, double y0, double y1) {
    return CornerSolidAngle(x1, y1) - CornerSolidAngle(x0, y1) - CornerSolidAngle(x1, y0) +
           CornerSolidAngle(x0, y0);
}

}  // namespace

ProjectionLight::ProjectionLight(const Transform &renderFromLight, const RGB &I,
                                 std::shared_ptr<const Image> map, double fovDeg, bool upright)
    : pos_(Vec3f(renderFromLight.Point(Vec3d(0, 0, 0)))),
      axis_(Vec3f(Normalize(renderFromLight.Vector(Vec3d(0, 0, 1))))),
      renderFromLight_(renderFromLight),
      lightFromRender_(renderFromLight.Inverse()),
      I_(I),
      map_(std::move(map)),
      upright_(upright) {
    // pbrt-v3: the screen window is the image's aspect ratio, fov across its shorter side.
    const double aspect = map_ ? double(map_->width) / map_->height : 1.0;
    const double t = std::tan(Radians(fovDeg) / 2);
    sx_ = aspect > 1 ? t * aspect : t;
    sy_ = aspect > 1 ? t : t / aspect;
    // The cone through the frustum's corners (pbrt-v3's corner formula holds only for images
    // at most as wide as tall; this one holds for both).
    cosTotalWidth_ = 1 / std::sqrt(1 + sx_ * sx_ + sy_ * sy_);
    if (!map_) {
        mapIntegral_ = RectSolidAngle(-sx_, sx_, -sy_, sy_);
        return;
    }
    const int w = map_->width, h = map_->height;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // Row 0 lies at the frustum's -y (pbrt-v3 looks the image up from the screen
            // window's lower corner; upright, at +y: the mirror rectangle, the same solid
            // angle).
            const double x0 = -sx_ + 2 * sx_ * x / w, x1 = -sx_ + 2 * sx_ * (x + 1) / w;
            const double y0 = -sy_ + 2 * sy_ * y / h, y1 = -sy_ + 2 * sy_ * (y + 1) / h;
            mapIntegral_ += double(map_->GetRGB(x, y).Luminance()) * RectSolidAngle(x0, x1, y0, y1);
        }
}

RGB ProjectionLight::Projection(const Vec3f &w) const {
    const Vec3d wl = lightFromRender_.Vector(Vec3d(w));
    // pbrt-v3's near plane at 1e-3 (for a unit direction).
    if (!(wl.z >= 1e-3 * Length(wl))) return RGB(0);
    const double px = wl.x / wl.z, py = wl.y / wl.z;
    if (!(std::abs(px) <= sx_ && std::abs(py) <= sy_)) return RGB(0);
    if (!map_) return RGB(1);
    if (upright_) {
        const int x = Clamp(int((px + sx_) / (2 * sx_) * map_->width), 0, map_->width - 1);
        const int y = Clamp(int((sy_ - py) / (2 * sy_) * map_->height), 0, map_->height - 1);
        return map_->GetRGB(x, y);
    }
    return ImageBilerp(*map_, (px + sx_) / (2 * sx_), (py + sy_) / (2 * sy_), false);
}

bool ProjectionLight::SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const {
    float dist2;
    if (!SamplePointPosition(pos_, si, ls, &dist2)) return false;
    ls->Li = I_ * Projection(-ls->wi) / dist2;
    return !ls->Li.IsBlack();
}

bool ProjectionLight::SampleLe(Vec2f, Vec2f uDir, const SceneSphere &, LightLeSample *ls) const {
    const Vec3f wl = UniformConeDirection(uDir, float(cosTotalWidth_));
    const Vec3f w = Vec3f(Normalize(renderFromLight_.Vector(Vec3d(wl))));
    ls->ray = Ray{pos_, w};
    ls->n = Vec3f(0, 0, 0);
    ls->Le = I_ * Projection(w);
    ls->pdfPos = 1;
    ls->pdfDir = float(1 / (2 * Pi * (1 - cosTotalWidth_)));
    return true;
}

void ProjectionLight::PdfLe(const Vec3f &, const Vec3f &, const Vec3f &w, const SceneSphere &,
                            float *pdfPos, float *pdfDir) const {
    *pdfPos = 0;
    *pdfDir =
        Dot(w, axis_) >= float(cosTotalWidth_) ? float(1 / (2 * Pi * (1 - cosTotalWidth_))) : 0.f;
}

// LightSource "projection" (light_list.inc). Parameters:
//   I         spectrum  1       radiant intensity (times the map)
//   scale     spectrum  1       multiplies I
//   fov       float     45      the frustum's angle across the image's shorter side,
//                               degrees (pbrt-v4's default, in a file read by its rules: 90)
//   mapname   string    ""      the image thrown along the light's +z: its columns left to
//                               right along +x, its rows top to bottom along +y (pbrt-v3: the
//                               image lands upside down on a wall the light faces, with +y
//                               up); none: a square frustum of constant intensity
//   filename  string    ""      pbrt-v4: the image thrown upright (rows top to bottom along
//                               -y), looked up at the nearest texel; not with mapname
//   power     float     (none)  pbrt-v4: the radiant power; I is scaled by it over the map's
//                               luminance integrated over the frustum
// The light sits at the origin of its coordinate system (pbrt-v3 reads no "from").
std::unique_ptr<Light> CreateProjectionLight(const LightInputs &in) {
    const LightParams &p = in.params;
    const RGB I = p.Spectrum("I", RGB(1)) * p.Scale();
    const float fov = p.Float("fov", in.pbrtVersion == 4 ? 90.f : 45.f);
    if (!(fov > 0 && fov < 180))
        throw SceneError(p.Loc("fov"), "projection light fov must be between 0 and 180 degrees");
    const bool upright = !p.String("filename", "").empty();
    if (upright && !p.String("mapname", "").empty())
        throw SceneError(p.Loc("filename"),
                         "projection light: give \"mapname\" (pbrt-v3, thrown upside down) or "
                         "\"filename\" (pbrt-v4, upright), not both");
    const std::shared_ptr<const Image> map = p.OptionalImage(upright ? "filename" : "mapname");
    const ProjectionLight unscaled(in.renderFromLight, RGB(1), map, fov, upright);
    const RGB scaled = PhotometricScale(p, I, "power", unscaled.MapIntegral(), in.loc);
    return std::make_unique<ProjectionLight>(in.renderFromLight, scaled, map, fov, upright);
}

}  // namespace prism
