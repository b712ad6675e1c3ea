#include "render/area_light.h"

#include <cmath>

#include "image/image.h"

namespace prism {

DiffuseAreaLight::DiffuseAreaLight(const AnalyticShape *analytic, const TriangleMesh *mesh,
                                   const RGB &L, bool twoSided, int nSamples)
    : analytic_(analytic), mesh_(mesh), Lemit_(L), twoSided_(twoSided), nSamples_(std::max(1, nSamples)) {
    if (mesh_) {
        std::vector<double> areas(mesh_->NumTriangles());
        for (size_t i = 0; i < areas.size(); ++i) {
            const uint32_t *v = mesh_->Triangle(i);
            Vec3d p0(mesh_->Position(v[0])), p1(mesh_->Position(v[1])), p2(mesh_->Position(v[2]));
            areas[i] = 0.5 * Length(Cross(p1 - p0, p2 - p0));
            meshArea_ += areas[i];
        }
        triangleAreas_ = Distribution1D(std::move(areas));
    }
}

bool DiffuseAreaLight::SampleLi(const SurfaceInteraction &si, Vec2f u, LightSample *ls) const {
    Vec3f p, n;
    float pdf;
    if (analytic_) {
        ShapeSample ss;
        if (!analytic_->Sample(si.p, u, &ss)) return false;
        p = ss.p;
        n = ss.n;
        pdf = ss.pdf;
    } else {
        if (!(meshArea_ > 0)) return false;
        // Choose a triangle by area, reusing u.x, then a uniform point on it.
        double prob;
        int tri = triangleAreas_.SampleDiscrete(u.x, &prob);
        // Remap u.x within the chosen triangle's CDF interval to keep stratification.
        double uxr = prob > 0 ? Clamp((u.x - triangleAreas_.Cdf(tri)) / prob, 0.0, 0x1.fffffffffffffp-1)
                              : 0.5;
        double su0 = std::sqrt(uxr);
        double b0 = 1 - su0, b1 = u.y * su0;
        const uint32_t *v = mesh_->Triangle(size_t(tri));
        Vec3d p0(mesh_->Position(v[0])), p1(mesh_->Position(v[1])), p2(mesh_->Position(v[2]));
        Vec3d pw = p0 * b0 + p1 * b1 + p2 * (1 - b0 - b1);
        n = mesh_->GeometricNormal(size_t(tri));
        if (n == Vec3f(0, 0, 0)) return false;
        p = Vec3f(pw);
        Vec3f w = p - si.p;
        float dist2 = LengthSquared(w);
        float cosLight = AbsDot(n, w) / std::sqrt(dist2);
        if (!(dist2 > 0) || cosLight == 0) return false;
        pdf = float(1 / meshArea_ * dist2 / cosLight);
    }
    Vec3f w = p - si.p;
    float dist = Length(w);
    if (!(dist > 0) || !(pdf > 0) || !std::isfinite(pdf)) return false;
    ls->wi = w / dist;
    ls->Li = L(n, -ls->wi);
    ls->pLight = p;
    ls->infinite = false;
    ls->pdf = pdf;
    return true;
}

InfiniteLight::InfiniteLight(const Transform &renderFromLight, const RGB &L,
                             std::shared_ptr<const Image> map, int nSamples)
    : renderFromLight_(renderFromLight), L_(L), map_(std::move(map)), nSamples_(std::max(1, nSamples)) {
    if (map_) {
        // Sample texels in proportion to luminance times sin(theta) (the equirectangular
        // area distortion), as pbrt-v3's InfiniteAreaLight does.
        int w = map_->width, h = map_->height;
        std::vector<double> f(size_t(w) * size_t(h));
        for (int y = 0; y < h; ++y) {
            double sinTheta = std::sin(Pi * (y + 0.5) / h);
            for (int x = 0; x < w; ++x)
                f[size_t(y) * size_t(w) + size_t(x)] = double(map_->GetRGB(x, y).Luminance()) * sinTheta;
        }
        distribution_ = Distribution2D(f, w, h);
    }
}

RGB InfiniteLight::Lookup(const Vec3f &wRender) const {
    if (!map_) return L_;
    Vec3d wl = Normalize(renderFromLight_.Inverse().Vector(Vec3d(wRender)));
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

RGB InfiniteLight::Le(const Ray &ray) const { return Lookup(ray.d); }

bool InfiniteLight::SampleLi(const SurfaceInteraction &si, Vec2f u, LightSample *ls) const {
    Vec3f wi;
    float pdf;
    if (!map_) {
        // Cosine-weighted hemisphere on the side of the viewer (matches the Lambertian lobe).
        Vec3f n = FaceForward(si.ns, si.wo);
        float r = std::sqrt(u.x), phi = float(2 * Pi) * u.y;
        Vec3f lx = Vec3f(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.f, 1 - u.x)));
        Vec3f s, t;
        CoordinateSystem(n, &s, &t);
        wi = s * lx.x + t * lx.y + n * lx.z;
        pdf = lx.z * float(InvPi);
    } else {
        double mapPdf;
        Vec2d uv = distribution_.SampleContinuous(Vec2d(u.x, u.y), &mapPdf);
        if (mapPdf == 0) return false;
        double theta = uv.y * Pi, phi = uv.x * 2 * Pi;
        double sinTheta = std::sin(theta);
        if (sinTheta == 0) return false;
        Vec3d wl(sinTheta * std::cos(phi), sinTheta * std::sin(phi), std::cos(theta));
        wi = Vec3f(Normalize(renderFromLight_.Vector(wl)));
        pdf = float(mapPdf / (2 * Pi * Pi * sinTheta));
    }
    if (!(pdf > 0)) return false;
    ls->wi = wi;
    ls->Li = Lookup(wi);
    ls->infinite = true;
    ls->pdf = pdf;
    return true;
}

}  // namespace prism
