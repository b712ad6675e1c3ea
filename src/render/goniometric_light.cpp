#include "render/goniometric_light.h"

#include <cmath>

#include "core/equal_area.h"
#include "image/image.h"

namespace prism {

RGB ImageBilerp(const Image &image, double s, double t, bool wrapS) {
    const int w = image.width, h = image.height;
    const double x = s * w - 0.5, y = t * h - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const float dx = float(x - fx), dy = float(y - fy);
    // Far-off coordinates are clamped before the conversion to int.
    const int x0 = int(Clamp(fx, -2.0, double(w) + 1)), y0 = int(Clamp(fy, -2.0, double(h) + 1));
    auto texel = [&](int i, int j) {
        i = wrapS ? ((i % w) + w) % w : Clamp(i, 0, w - 1);
        return image.GetRGB(i, Clamp(j, 0, h - 1));
    };
    return texel(x0, y0) * ((1 - dx) * (1 - dy)) + texel(x0 + 1, y0) * (dx * (1 - dy)) +
           texel(x0, y0 + 1) * ((1 - dx) * dy) + texel(x0 + 1, y0 + 1) * (dx * dy);
}

GoniometricLight::GoniometricLight(const Transform &renderFromLight, const RGB &I,
                                   std::shared_ptr<const Image> map, bool equalArea)
    : pos_(Vec3f(renderFromLight.Point(Vec3d(0, 0, 0)))),
      lightFromRender_(renderFromLight.Inverse()),
      I_(I),
      map_(std::move(map)),
      equalArea_(equalArea) {
    if (!map_) return;
    if (equalArea_) {
        // pbrt-v4 keeps the mean of each texel's R, G and B; texels are equal solid angles.
        auto grey = std::make_shared<Image>(map_->width, map_->height, 1);
        double sum = 0;
        for (int y = 0; y < map_->height; ++y)
            for (int x = 0; x < map_->width; ++x) {
                const float g = map_->GetRGB(x, y).Average();
                grey->At(x, y, 0) = g;
                sum += g;
            }
        mapAverage_ = sum / (double(map_->width) * map_->height);
        map_ = std::move(grey);
        return;
    }
    // The average over the sphere: row y spans theta in [y, y + 1] pi / h, whose share of the
    // sphere's solid angle is (cos theta0 - cos theta1) / 2.
    const int w = map_->width, h = map_->height;
    double sum = 0;
    for (int y = 0; y < h; ++y) {
        double row = 0;
        for (int x = 0; x < w; ++x) row += double(map_->GetRGB(x, y).Luminance());
        sum += row / w * 0.5 * (std::cos(Pi * y / h) - std::cos(Pi * (y + 1) / h));
    }
    mapAverage_ = sum;
}

RGB GoniometricLight::Scale(const Vec3f &w) const {
    if (!map_) return RGB(1);
    if (equalArea_) {
        // Light space with y and z swapped, as pbrt-v4 does, then the nearest texel.
        const Vec3d wl = Normalize(lightFromRender_.Vector(Vec3d(w)));
        const Vec2d uv = EqualAreaSphereToSquare(Vec3d(wl.x, wl.z, wl.y));
        const int x = Clamp(int(uv.x * map_->width), 0, map_->width - 1);
        const int y = Clamp(int(uv.y * map_->height), 0, map_->height - 1);
        return RGB(map_->At(x, y, 0));
    }
    // Light space with y and z swapped: theta from +y, phi from +x toward +z (pbrt-v3).
    const Vec3d wl = Normalize(lightFromRender_.Vector(Vec3d(w)));
    const double theta = SafeACos(wl.y);
    double phi = std::atan2(wl.z, wl.x);
    if (phi < 0) phi += 2 * Pi;
    return ImageBilerp(*map_, phi / (2 * Pi), theta / Pi, true);
}

bool GoniometricLight::SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const {
    float dist2;
    if (!SamplePointPosition(pos_, si, ls, &dist2)) return false;
    ls->Li = I_ * Scale(-ls->wi) / dist2;
    return !ls->Li.IsBlack();
}

bool GoniometricLight::SampleLe(Vec2f, Vec2f uDir, const SceneSphere &, LightLeSample *ls) const {
    const Vec3f w = UniformSphereDirection(uDir);
    ls->ray = Ray{pos_, w};
    ls->n = Vec3f(0, 0, 0);
    ls->Le = I_ * Scale(w);
    ls->pdfPos = 1;
    ls->pdfDir = float(1 / (4 * Pi));
    return true;
}

void GoniometricLight::PdfLe(const Vec3f &, const Vec3f &, const Vec3f &, const SceneSphere &,
                             float *pdfPos, float *pdfDir) const {
    *pdfPos = 0;
    *pdfDir = float(1 / (4 * Pi));
}

// LightSource "goniometric" (light_list.inc). Parameters:
//   I         spectrum  1       radiant intensity (times the map)
//   scale     spectrum  1       multiplies I
//   mapname   string    ""      an image over the sphere of directions: column u = phi / 2 pi
//                               (phi from the light's +x toward +z), row v = theta / pi
//                               (theta from the light's +y, row 0 at the top); none: a point
//                               light
//   filename  string    ""      pbrt-v4: a square equal-area image (core/equal_area.h) of
//                               the light's directions with y and z swapped (+y at its
//                               centre), looked up at the nearest texel, R, G and B
//                               averaged; not with mapname
//   power     float     (none)  pbrt-v4: the radiant power; I is scaled by it over 4 pi x the
//                               map's mean
// The light sits at the origin of its coordinate system (pbrt-v3 reads no "from").
std::unique_ptr<Light> CreateGoniometricLight(const LightInputs &in) {
    const LightParams &p = in.params;
    const auto [map, equalArea] = ReadSphereMap(p, "goniometric light");
    const RGB I = p.Spectrum("I", RGB(1)) * p.Scale();
    const GoniometricLight unscaled(in.renderFromLight, RGB(1), map, equalArea);
    const RGB scaled = PhotometricScale(p, I, "power", 4 * Pi * unscaled.MapAverage(), in.loc);
    return std::make_unique<GoniometricLight>(in.renderFromLight, scaled, map, equalArea);
}

}  // namespace prism
