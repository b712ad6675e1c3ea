#include "render/area_light.h"

#include <cmath>

namespace prism {

DiffuseAreaLight::DiffuseAreaLight(const AnalyticShape *analytic, const TriangleMesh *mesh,
                                   const RGB &L, bool twoSided, int nSamples)
    : analytic_(analytic),
      mesh_(mesh),
      Lemit_(L),
      twoSided_(twoSided),
      nSamples_(std::max(1, nSamples)) {
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
        double uxr = prob > 0
                         ? Clamp((u.x - triangleAreas_.Cdf(tri)) / prob, 0.0, 0x1.fffffffffffffp-1)
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

double DiffuseAreaLight::Power(double) const {
    double area = meshArea_;
    if (analytic_) {
        // Uniform area sampling's object-space density, through the area Jacobian at one point
        // (exact for similarity transforms, an estimate otherwise: it only weighs the choice).
        Vec3d p, n;
        double pdf;
        if (!analytic_->SampleObjectArea(Vec2f(0.5f, 0.5f), &p, &n, &pdf) || !(pdf > 0)) return 0;
        const Transform &m = analytic_->RenderFromObject();
        double len = Length(n);
        double jac =
            len > 0 ? std::abs(m.Matrix().Determinant3x3()) * Length(m.Normal(n / len)) : 1.0;
        area = jac / pdf;
    }
    return (twoSided_ ? 2 : 1) * Pi * area * Lemit_.Luminance();
}

float DiffuseAreaLight::PdfLi(const SurfaceInteraction &ref, const Vec3f &wi,
                              const SurfaceInteraction *hit) const {
    if (!hit) return 0;
    if (analytic_) return analytic_->Pdf(ref.p, hit->p, hit->n);
    // SampleLi: a triangle by area, then a uniform point on it: 1 / area over the mesh.
    Vec3f w = hit->p - ref.p;
    float dist2 = LengthSquared(w);
    float cosLight = AbsDot(hit->n, wi);
    if (!(dist2 > 0) || cosLight == 0 || !(meshArea_ > 0)) return 0;
    return float(1 / meshArea_ * dist2 / cosLight);
}

}  // namespace prism
