#include "render/infinite_light.h"

#include <algorithm>
#include <cmath>

#include "core/equal_area.h"
#include "image/image.h"

namespace prism {

InfiniteLight::InfiniteLight(const Transform &renderFromLight, const RGB &L,
                             std::shared_ptr<const Image> map, int nSamples, Projection projection,
                             std::optional<LightPortal> portal)
    : renderFromLight_(renderFromLight),
      L_(L),
      map_(std::move(map)),
      projection_(projection),
      nSamples_(std::max(1, nSamples)),
      portal_(portal) {
    if (map_ && projection_ == Projection::EqualArea) {
        // Every texel is the same solid angle: sample by luminance alone (negative texels,
        // which emit nothing, never).
        const int w = map_->width, h = map_->height;
        std::vector<double> f(size_t(w) * size_t(h));
        double sum = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                sum += f[size_t(y) * size_t(w) + size_t(x)] =
                    double(map_->GetRGB(x, y).Clamped(0.f, INFINITY).Luminance());
        distribution_ = Distribution2D(f, w, h);
        if (portal_) {
            // Power counts the texels facing the portal's outer side only (half of those
            // whose centre lies on its plane).
            sum = 0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const Vec3d d = EqualAreaSquareToSphere({(x + 0.5) / w, (y + 0.5) / h});
                    const double c = Dot(Vec3d(portal_->n), renderFromLight_.Vector(d));
                    const double share = c > 1e-9 ? 1 : c >= -1e-9 ? 0.5 : 0;
                    sum += share * f[size_t(y) * size_t(w) + size_t(x)];
                }
        }
        averageLuminance_ = sum / (double(w) * h) * L_.Luminance();
    } else if (map_) {
        // Sample texels in proportion to luminance times sin(theta) (the equirectangular
        // area distortion), as pbrt-v3's InfiniteAreaLight does.
        int w = map_->width, h = map_->height;
        std::vector<double> f(size_t(w) * size_t(h));
        for (int y = 0; y < h; ++y) {
            double sinTheta = std::sin(Pi * (y + 0.5) / h);
            for (int x = 0; x < w; ++x)
                f[size_t(y) * size_t(w) + size_t(x)] =
                    double(map_->GetRGB(x, y).Luminance()) * sinTheta;
        }
        distribution_ = Distribution2D(f, w, h);
        double sum = 0, wsum = 0;
        for (int y = 0; y < h; ++y) {
            double sinTheta = std::sin(Pi * (y + 0.5) / h);
            for (int x = 0; x < w; ++x) sum += f[size_t(y) * size_t(w) + size_t(x)];
            wsum += sinTheta * w;
        }
        averageLuminance_ = wsum > 0 ? sum / wsum * L_.Luminance() : 0;
    } else {
        averageLuminance_ = L_.Luminance();
    }
}

RGB InfiniteLight::Lookup(const Vec3f &wRender) const {
    if (!map_) return L_;
    Vec3d wl = Normalize(renderFromLight_.Inverse().Vector(Vec3d(wRender)));
    if (projection_ == Projection::EqualArea) {
        // The texel the direction falls in, negatives clamped (pbrt-v4's ImageLe).
        const Vec2d uv = EqualAreaSphereToSquare(wl);
        const int x = Clamp(int(uv.x * map_->width), 0, map_->width - 1);
        const int y = Clamp(int(uv.y * map_->height), 0, map_->height - 1);
        return map_->GetRGB(x, y).Clamped(0.f, INFINITY) * L_;
    }
    double theta = SafeACos(wl.z), phi = std::atan2(wl.y, wl.x);
    if (phi < 0) phi += 2 * Pi;
    // Row 0 of the map is the +z pole; bilinear lookup with wrapping in phi.
    double s = phi / (2 * Pi) * map_->width - 0.5, t = theta / Pi * map_->height - 0.5;
    int s0 = int(std::floor(s)), t0 = int(std::floor(t));
    double ds = s - s0, dt = t - t0;
    auto texel = [&](int x, int y) {
        x = ((x % map_->width) + map_->width) % map_->width;
        y = Clamp(y, 0, map_->height - 1);
        return map_->GetRGB(x, y);
    };
    RGB v = texel(s0, t0) * float((1 - ds) * (1 - dt)) + texel(s0 + 1, t0) * float(ds * (1 - dt)) +
            texel(s0, t0 + 1) * float((1 - ds) * dt) + texel(s0 + 1, t0 + 1) * float(ds * dt);
    return v * L_;
}

RGB InfiniteLight::Le(const Ray &ray) const { return Faces(ray.d) ? Lookup(ray.d) : RGB(0); }

bool InfiniteLight::SamplePortal(const Vec3f &p, Vec2f u, Vec3f *wi, float *pdf) const {
    const LightPortal &q = *portal_;
    if (!(Dot(p - q.p0, q.n) < 0)) return false;  // on the outer side, or on its plane
    const Vec3f d = q.p0 + q.u * u.x + q.v * u.y - p;
    const float dist2 = LengthSquared(d);
    *wi = d / std::sqrt(dist2);
    const float cosine = Dot(*wi, q.n);
    *pdf = dist2 / (q.area * cosine);
    return cosine > 0 && std::isfinite(*pdf);
}

float InfiniteLight::PortalPdf(const Vec3f &p, const Vec3f &wi) const {
    const LightPortal &q = *portal_;
    const Vec3f w = Normalize(wi);
    const float cosine = Dot(w, q.n), depth = Dot(q.p0 - p, q.n);
    if (!(cosine > 0) || !(depth > 0)) return 0;
    const float t = depth / cosine;
    const Vec3f h = p + w * t - q.p0;
    const float a = Dot(h, q.u) / LengthSquared(q.u), b = Dot(h, q.v) / LengthSquared(q.v);
    if (!(a >= 0 && a <= 1 && b >= 0 && b <= 1)) return 0;
    return t * t / (q.area * cosine);
}

bool InfiniteLight::SampleMap(Vec2f u, Vec3f *wi, float *pdf) const {
    double mapPdf;
    Vec2d uv = distribution_.SampleContinuous(Vec2d(u.x, u.y), &mapPdf);
    if (mapPdf == 0) return false;
    if (projection_ == Projection::EqualArea) {
        *wi = Vec3f(Normalize(renderFromLight_.Vector(EqualAreaSquareToSphere(uv))));
        *pdf = float(mapPdf / (4 * Pi));
    } else {
        double theta = uv.y * Pi, phi = uv.x * 2 * Pi;
        double sinTheta = std::sin(theta);
        if (sinTheta == 0) return false;
        Vec3d wl(sinTheta * std::cos(phi), sinTheta * std::sin(phi), std::cos(theta));
        *wi = Vec3f(Normalize(renderFromLight_.Vector(wl)));
        *pdf = float(mapPdf / (2 * Pi * Pi * sinTheta));
    }
    return true;
}

bool InfiniteLight::SampleLi(const SurfaceInteraction &si, Vec2f u, LightSample *ls) const {
    Vec3f wi;
    float pdf;
    if (portal_) {
        if (!SamplePortal(si.p, u, &wi, &pdf)) return false;
    } else if (!map_ && LengthSquared(si.ns) == 0) {
        // A point inside a medium (volpath), which has no normal: the whole sphere.
        const float z = 1 - 2 * u.x, r = std::sqrt(std::max(0.f, 1 - z * z));
        const float phi = float(2 * Pi) * u.y;
        wi = Vec3f(r * std::cos(phi), r * std::sin(phi), z);
        pdf = float(1 / (4 * Pi));
    } else if (!map_) {
        // Cosine-weighted hemisphere on the side of the viewer (matches the Lambertian lobe).
        Vec3f n = FaceForward(si.ns, si.wo);
        float r = std::sqrt(u.x), phi = float(2 * Pi) * u.y;
        Vec3f lx = Vec3f(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.f, 1 - u.x)));
        Vec3f s, t;
        CoordinateSystem(n, &s, &t);
        wi = s * lx.x + t * lx.y + n * lx.z;
        pdf = lx.z * float(InvPi);
    } else if (!SampleMap(u, &wi, &pdf)) {
        return false;
    }
    if (!(pdf > 0)) return false;
    ls->wi = wi;
    ls->Li = Lookup(wi);
    ls->infinite = true;
    ls->pdf = pdf;
    return true;
}

float InfiniteLight::PdfLi(const SurfaceInteraction &ref, const Vec3f &wi,
                           const SurfaceInteraction *) const {
    if (portal_) return PortalPdf(ref.p, wi);
    if (!map_ && LengthSquared(ref.ns) == 0) return float(1 / (4 * Pi));  // in a medium
    if (!map_) {
        // SampleLi's cosine-weighted hemisphere about the shading normal on the viewer's side.
        float c = Dot(FaceForward(ref.ns, ref.wo), wi);
        return c > 0 ? c * float(InvPi) : 0.f;
    }
    return DirectionPdf(wi);
}

float InfiniteLight::DirectionPdf(const Vec3f &wi) const {
    if (!map_) return float(1 / (4 * Pi));
    Vec3d wl = Normalize(renderFromLight_.Inverse().Vector(Vec3d(wi)));
    if (projection_ == Projection::EqualArea)
        return float(distribution_.Pdf(EqualAreaSphereToSquare(wl)) / (4 * Pi));
    double theta = SafeACos(wl.z), phi = std::atan2(wl.y, wl.x);
    if (phi < 0) phi += 2 * Pi;
    double sinTheta = std::sin(theta);
    if (sinTheta == 0) return 0;
    return float(distribution_.Pdf(Vec2d(phi / (2 * Pi), theta / Pi)) / (2 * Pi * Pi * sinTheta));
}

bool InfiniteLight::SampleLe(Vec2f uPos, Vec2f uDir, const SceneSphere &sphere,
                             LightLeSample *ls) const {
    Vec3f wi;
    float pdf;
    if (!map_) {
        wi = UniformSphereDirection(uDir);
        pdf = float(1 / (4 * Pi));
    } else {
        // The map's own distribution, as SampleLi draws it without a portal.
        if (!SampleMap(uDir, &wi, &pdf)) return false;
    }
    if (!(pdf > 0)) return false;
    ls->ray = Ray{DiskOrigin(sphere, -wi, uPos), -wi};
    ls->n = Vec3f(0, 0, 0);
    ls->Le = Faces(wi) ? Lookup(wi) : RGB(0);
    ls->pdfPos = float(1 / (Pi * double(sphere.radius) * sphere.radius));
    ls->pdfDir = pdf;
    return true;
}

void InfiniteLight::PdfLe(const Vec3f &, const Vec3f &, const Vec3f &w, const SceneSphere &sphere,
                          float *pdfPos, float *pdfDir) const {
    *pdfPos = float(1 / (Pi * double(sphere.radius) * sphere.radius));
    *pdfDir = DirectionPdf(-w);
}

namespace {

// pbrt-v4's "portal": four corners of a rectangle (each edge parallel to the opposite one and
// perpendicular to its neighbours, to 0.001 in cosine, as pbrt-v4 requires), in world space.
LightPortal ReadPortal(const LightParams &p, bool hasEqualAreaMap,
                       const Transform &renderFromWorld) {
    const FileLoc loc = p.Loc("portal");
    if (!hasEqualAreaMap)
        throw SceneError(loc,
                         "infinite light: a \"portal\" needs the map of \"filename\" (as in "
                         "pbrt-v4)");
    const std::vector<Vec3f> c = p.Point3s("portal");
    if (c.size() != 4)
        throw SceneError(
            loc, "infinite light: \"portal\" needs 4 points, not " + std::to_string(c.size()));
    Vec3f q[4];
    for (int i = 0; i < 4; ++i) {
        q[i] = renderFromWorld.Point(c[size_t(i)]);
        if (!std::isfinite(q[i].x) || !std::isfinite(q[i].y) || !std::isfinite(q[i].z))
            throw SceneError(loc, "infinite light: \"portal\" points must be finite");
    }
    const Vec3f e01 = q[1] - q[0], e12 = q[2] - q[1], e32 = q[2] - q[3], e03 = q[3] - q[0];
    for (const Vec3f &e : {e01, e12, e32, e03})
        if (!(Length(e) > 0))
            throw SceneError(loc, "infinite light: \"portal\" has an edge of length 0");
    auto cosine = [](const Vec3f &a, const Vec3f &b) { return Dot(Normalize(a), Normalize(b)); };
    if (std::abs(cosine(e01, e32) - 1) > 1e-3f || std::abs(cosine(e12, e03) - 1) > 1e-3f ||
        std::abs(cosine(e01, e12)) > 1e-3f || std::abs(cosine(e12, e32)) > 1e-3f ||
        std::abs(cosine(e32, e03)) > 1e-3f || std::abs(cosine(e03, e01)) > 1e-3f)
        throw SceneError(loc,
                         "infinite light: \"portal\" is not a rectangle (corners in order, "
                         "each edge perpendicular to the next)");
    LightPortal portal;
    portal.p0 = q[0];
    portal.u = e03;
    portal.v = e01;
    const Vec3f n = Cross(e03, e01);
    portal.area = Length(n);
    portal.n = n / portal.area;
    return portal;
}

}  // namespace

// The most samples an infinite light may take per shading point.
inline constexpr int MaxInfiniteLightSamples = 4096;

// LightSource "infinite" (light_list.inc). Parameters:
//   L                   spectrum  1   radiance (times the map's texels)
//   scale               spectrum  1   multiplies L
//   mapname             string    ""  an equirectangular image, z the pole (u = phi / 2 pi)
//   filename            string    ""  pbrt-v4: a square equal-area image (core/equal_area.h),
//                                     z at its centre; not with mapname
//   nsamples (samples)  integer   1   light samples per shading point, 1 to 4096;
//                                     --light-samples wins
//   illuminance         float     (none)  pbrt-v4: the irradiance on an upward (+z in the
//                                     light's space) surface from the upper hemisphere; L is
//                                     scaled by it over the map's own (pi without a map)
//   portal              point3[]  (none)  pbrt-v4: four corners of a rectangle in world
//                                     space (a window) through which the map's light enters:
//                                     only directions toward the side (p3 - p0) x (p1 - p0)
//                                     points to emit; needs "filename"
std::unique_ptr<Light> CreateInfiniteLight(const LightInputs &in) {
    const LightParams &p = in.params;
    const SphereMap sphereMap = ReadSphereMap(p, "infinite light");
    const bool equalArea = sphereMap.equalArea;
    const std::shared_ptr<const Image> &map = sphereMap.image;
    // The map's irradiance on an upward surface. Equal-area, as pbrt-v4 computes it: each
    // texel above the horizon weighted by cos theta at its centre, times 2 pi / (w h) — half a
    // texel's solid angle, 4 pi / (w h), so pbrt-v4's map lights come out twice the
    // illuminance asked for (measured: an 8x8 white map at "illuminance" 10 lights a white
    // diffuse plane to radiance 6.795 in pbrt-v4, where 10 / pi would be 3.18). Prism renders
    // what pbrt-v4 renders. Latitude-longitude (Prism's reading of "mapname" with it): each row's
    // mean luminance times the integral of cos theta over its band of the upper hemisphere, 2 pi
    // (sin^2 theta1 - sin^2 theta0) / 2 (rows from theta 0 at the +z pole: exact for texels
    // constant over their band).
    double k_e = Pi;
    if (map && equalArea && p.Has("illuminance")) {
        k_e = 0;
        const int w = map->width, h = map->height;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const Vec3d d = EqualAreaSquareToSphere({(x + 0.5) / w, (y + 0.5) / h});
                if (d.z > 0)
                    k_e += double(map->GetRGB(x, y).Clamped(0.f, INFINITY).Luminance()) * d.z;
            }
        k_e *= 2 * Pi / (double(w) * h);
    } else if (map && p.Has("illuminance")) {
        k_e = 0;
        const int w = map->width, h = map->height;
        for (int y = 0; y < h && 2 * y < h; ++y) {
            const double t0 = Pi * y / h, t1 = std::min(Pi * (y + 1) / h, Pi / 2);
            double row = 0;
            for (int x = 0; x < w; ++x) row += double(map->GetRGB(x, y).Luminance());
            const double s0 = std::sin(t0), s1 = std::sin(t1);
            k_e += row / w * Pi * (s1 * s1 - s0 * s0);
        }
    }
    const RGB L0 = p.Spectrum("L", RGB(1)) * p.Scale();
    const RGB L = p.Has("illuminance") && !(k_e > 0)
                      ? RGB(0)
                      : PhotometricScale(p, L0, "illuminance", k_e, in.loc);
    int n = p.Int("nsamples", p.Int("samples", 1));
    if (in.lightSamples > 0) n = in.lightSamples;
    if (n < 1 || n > MaxInfiniteLightSamples)
        throw SceneError(in.loc, "infinite light nsamples must be 1 to 4096");
    std::optional<LightPortal> portal;
    if (p.Has("portal")) portal = ReadPortal(p, map && equalArea, in.renderFromWorld);
    return std::make_unique<InfiniteLight>(
        in.renderFromLight, L, map, n,
        equalArea ? InfiniteLight::Projection::EqualArea : InfiniteLight::Projection::LatLong,
        portal);
}

}  // namespace prism
