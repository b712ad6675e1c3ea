#include "render/area_light.h"

#include <algorithm>
#include <cmath>

namespace prism {

int DiffuseAreaLight::TextureMeanSamples(double uvArea) {
    const double side = std::sqrt(2 * std::max(0.0, uvArea)) * 2048;
    return std::isfinite(side) ? std::clamp(int(std::ceil(side)), 1, 256) : 256;
}

namespace {

// The mean of the texture over triangle `tri`: its value at the centroids of the m² equal
// sub-triangles of an m × m barycentric grid.
RGB TriangleMean(const Texture &t, const TriangleMesh &mesh, size_t tri, int maxSide) {
    auto uvArea = [&](int set) {
        Vec2f a = mesh.UVAt(tri, 0, 0, set), b = mesh.UVAt(tri, 1, 0, set),
              c = mesh.UVAt(tri, 0, 1, set);
        return 0.5 * std::abs(double(b.x - a.x) * (c.y - a.y) - double(b.y - a.y) * (c.x - a.x));
    };
    const int m =
        std::min(maxSide, DiffuseAreaLight::TextureMeanSamples(std::max(uvArea(0), uvArea(1))));
    const uint32_t *v = mesh.Triangle(tri);
    const Vec3f p0 = mesh.Position(v[0]), p1 = mesh.Position(v[1]), p2 = mesh.Position(v[2]);
    RGB sum;
    const Vec3f normal = mesh.GeometricNormal(tri);
    auto at = [&](double b1, double b2) {
        const float u = float(b1), w = float(b2);
        TextureContext tc{mesh.UVAt(tri, u, w, 0), p0 * (1 - u - w) + p1 * u + p2 * w,
                          mesh.UVAt(tri, u, w, 1)};
        tc.n = normal;
        sum += t.Evaluate(tc).Clamped(0.f);
    };
    for (int i = 0; i < m; ++i)
        for (int j = 0; i + j < m; ++j) {
            at((i + 1 / 3.0) / m, (j + 1 / 3.0) / m);                     // upward
            if (i + j < m - 1) at((i + 2 / 3.0) / m, (j + 2 / 3.0) / m);  // downward
        }
    return sum / float(m * m);
}

}  // namespace

DiffuseAreaLight::DiffuseAreaLight(const AnalyticShape *analytic, const TriangleMesh *mesh,
                                   const RGB &L, bool twoSided, int nSamples, TexturePtr radiance,
                                   double powerPerTriangle)
    : analytic_(analytic),
      mesh_(mesh),
      Lemit_(L),
      twoSided_(twoSided),
      nSamples_(std::max(1, nSamples)),
      radiance_(mesh ? std::move(radiance) : nullptr) {
    if (mesh_) {
        triangleAreas_.resize(mesh_->NumTriangles());
        std::vector<double> weights(triangleAreas_.size());
        // The texture's mean luminance per triangle (1 untextured), for powerPerTriangle.
        std::vector<double> meanLuminance(weights.size(), 1.0);
        // At most about MaxTextureMeanLookups texture lookups for the whole mesh.
        const int maxSide = std::clamp(int(std::sqrt(double(MaxTextureMeanLookups) /
                                                     double(std::max<size_t>(1, weights.size())))),
                                       1, 256);
        for (size_t i = 0; i < weights.size(); ++i) {
            const uint32_t *v = mesh_->Triangle(i);
            Vec3d p0(mesh_->Position(v[0])), p1(mesh_->Position(v[1])), p2(mesh_->Position(v[2]));
            triangleAreas_[i] = 0.5 * Length(Cross(p1 - p0, p2 - p0));
            weights[i] = triangleAreas_[i];
            if (radiance_ && weights[i] > 0) {
                const RGB texMean = TriangleMean(*radiance_, *mesh_, i, maxSide);
                const RGB mean = texMean * Lemit_;
                weights[i] *= (double(mean.r) + mean.g + mean.b) / 3;
                meanLuminance[i] = texMean.Luminance();
            }
        }
        if (powerPerTriangle > 0) {
            // k: the luminance each triangle's power is measured by (pbrt-v4's k_e: its
            // image's mean, or 1, as an RGB L keeps its magnitude and any other spectrum has
            // luminance 1 already; L, with "scale", multiplies the result).
            double areaSum = 0, lumSum = 0;
            for (size_t i = 0; i < weights.size(); ++i) {
                areaSum += triangleAreas_[i];
                lumSum += triangleAreas_[i] * meanLuminance[i];
            }
            const double k = areaSum > 0 ? lumSum / areaSum : 0;
            // Each pbrt-v4 shape emits the power: a triangle, or a patch of several
            // (TriangleMesh::SetPatches), whose triangles share its area.
            std::vector<double> shapeArea(triangleAreas_);
            const std::vector<uint32_t> &first = mesh_->PatchFirstTriangles();
            for (size_t p = 0; p < first.size(); ++p) {
                const size_t end = p + 1 < first.size() ? first[p + 1] : weights.size();
                double a = 0;
                for (size_t i = first[p]; i < end; ++i) a += triangleAreas_[i];
                for (size_t i = first[p]; i < end; ++i) shapeArea[i] = a;
            }
            triangleScale_.resize(weights.size());
            for (size_t i = 0; i < weights.size(); ++i) {
                const double e = (twoSided_ ? 2 : 1) * Pi * shapeArea[i] * k;
                triangleScale_[i] = e > 0 ? float(powerPerTriangle / e) : 0.f;
                // Textured: sampled by power. Constant: by area, the radiance scaled on return.
                if (radiance_) weights[i] *= triangleScale_[i];
            }
        }
        for (size_t i = 0; i < weights.size(); ++i) {
            if (weights[i] > 0) {
                meshArea_ += triangleAreas_[i];
                sampledTriangles_++;
            }
        }
        triangleWeights_ = Distribution1D(std::move(weights));
        if (!(triangleWeights_.Integral() > 0)) meshArea_ = 0;  // nothing to sample
    }
}

double DiffuseAreaLight::PdfArea(int prim) const {
    if (!mesh_ || !(meshArea_ > 0) || prim < 0 || prim >= triangleWeights_.Count()) return 0;
    const double area = triangleAreas_[size_t(prim)];
    if (!radiance_) return area > 0 ? 1 / meshArea_ : 0;
    const double prob = triangleWeights_.Cdf(prim + 1) - triangleWeights_.Cdf(prim);
    return area > 0 && prob > 0 ? prob / area : 0;
}

bool DiffuseAreaLight::SampleLi(const SurfaceInteraction &si, Vec2f u, LightSample *ls) const {
    if (analytic_) {
        ShapeSample ss;
        if (!analytic_->Sample(si.p, u, &ss)) return false;
        return Finish(si, ss.p, ss.n, ss.pdf, Lemit_, ls);
    }
    if (!(meshArea_ > 0)) return false;
    // Choose a triangle by weight (area, × mean radiance when textured), reusing u.x, then a
    // uniform point on it.
    double prob;
    const int tri = triangleWeights_.SampleDiscrete(u.x, &prob);
    if (!(prob > 0)) return false;
    // Remap u.x within the chosen triangle's CDF interval to keep stratification.
    const double uxr = Clamp((u.x - triangleWeights_.Cdf(tri)) / prob, 0.0, 0x1.fffffffffffffp-1);
    // Density per unit area: prob / area of the triangle (1 / area of the mesh when the
    // triangles are chosen by area).
    const double pdfArea = radiance_ ? prob / triangleAreas_[size_t(tri)] : 1 / meshArea_;
    return SampleTriangle(si, tri, uxr, u.y, pdfArea, ls);
}

bool DiffuseAreaLight::SampleLiTriangle(const SurfaceInteraction &si, int tri, Vec2f u,
                                        LightSample *ls) const {
    if (!mesh_ || tri < 0 || size_t(tri) >= triangleAreas_.size() ||
        !(triangleAreas_[size_t(tri)] > 0))
        return false;
    return SampleTriangle(si, tri, u.x, u.y, 1 / triangleAreas_[size_t(tri)], ls);
}

bool DiffuseAreaLight::SampleTriangle(const SurfaceInteraction &si, int tri, double ux, float uy,
                                      double pdfArea, LightSample *ls) const {
    ls->prim = tri;
    const double su0 = std::sqrt(ux);
    const double b0 = 1 - su0, b1 = uy * su0;
    const uint32_t *v = mesh_->Triangle(size_t(tri));
    Vec3d p0(mesh_->Position(v[0])), p1(mesh_->Position(v[1])), p2(mesh_->Position(v[2]));
    const Vec3f p = Vec3f(p0 * b0 + p1 * b1 + p2 * (1 - b0 - b1));
    const Vec3f n = mesh_->GeometricNormal(size_t(tri));
    if (n == Vec3f(0, 0, 0)) return false;
    const Vec3f w = p - si.p;
    const float dist2 = LengthSquared(w);
    const float cosLight = AbsDot(n, w) / std::sqrt(dist2);
    if (!(dist2 > 0) || cosLight == 0) return false;
    RGB Le = Emitted(tri);
    // The texture only where the point emits toward si (else Li is 0 anyway).
    if (radiance_ && (twoSided_ || Dot(n, -w) > 0)) {
        // Embree's barycentrics of the point: u for vertex 1, v for vertex 2.
        const float eu = float(b1), ev = float(1 - b0 - b1);
        TextureContext tc{mesh_->UVAt(size_t(tri), eu, ev, 0), p,
                          mesh_->UVAt(size_t(tri), eu, ev, 1)};
        tc.n = n;
        Le = Le * radiance_->Evaluate(tc).Clamped(0.f);
    }
    return Finish(si, p, n, float(pdfArea * dist2 / cosLight), Le, ls);
}

bool DiffuseAreaLight::Finish(const SurfaceInteraction &si, const Vec3f &p, const Vec3f &n,
                              float pdf, const RGB &Le, LightSample *ls) const {
    const Vec3f w = p - si.p;
    const float dist = Length(w);
    if (!(dist > 0) || !(pdf > 0) || !std::isfinite(pdf)) return false;
    ls->wi = w / dist;
    ls->Li = (twoSided_ || Dot(n, -ls->wi) > 0) ? Le : RGB(0);
    ls->pLight = p;
    ls->infinite = false;
    ls->pdf = pdf;
    ls->n = n;
    return true;
}

float DiffuseAreaLight::PdfPosition(const Vec3f &n, int prim) const {
    return analytic_ ? analytic_->PdfArea(n) : float(PdfArea(prim));
}

bool DiffuseAreaLight::SampleLe(Vec2f uPos, Vec2f uDir, const SceneSphere &,
                                LightLeSample *ls) const {
    Vec3f p, n;
    float pdfPos;
    RGB Le = Lemit_;
    if (analytic_) {
        ShapeSample ss;
        if (!analytic_->SampleArea(uPos, &ss)) return false;
        p = ss.p, n = ss.n, pdfPos = ss.pdf;
    } else {
        if (!(meshArea_ > 0)) return false;
        // As SampleLi: a triangle by weight, uPos.x reused within it, a uniform point on it.
        double prob;
        const int tri = triangleWeights_.SampleDiscrete(uPos.x, &prob);
        if (!(prob > 0)) return false;
        Le = Emitted(tri);
        const double ux =
            Clamp((uPos.x - triangleWeights_.Cdf(tri)) / prob, 0.0, 0x1.fffffffffffffp-1);
        const double su0 = std::sqrt(ux), b0 = 1 - su0, b1 = uPos.y * su0;
        const uint32_t *v = mesh_->Triangle(size_t(tri));
        Vec3d p0(mesh_->Position(v[0])), p1(mesh_->Position(v[1])), p2(mesh_->Position(v[2]));
        p = Vec3f(p0 * b0 + p1 * b1 + p2 * (1 - b0 - b1));
        n = mesh_->GeometricNormal(size_t(tri));
        pdfPos = float(PdfArea(tri));
        if (n == Vec3f(0, 0, 0) || !(pdfPos > 0)) return false;
        if (radiance_) {
            const float eu = float(b1), ev = float(1 - b0 - b1);
            TextureContext tc{mesh_->UVAt(size_t(tri), eu, ev, 0), p,
                              mesh_->UVAt(size_t(tri), eu, ev, 1)};
            tc.n = n;
            Le = Le * radiance_->Evaluate(tc).Clamped(0.f);
        }
    }
    // A cosine-weighted direction about n (about -n for the back of a two-sided light).
    Vec3f axis = n;
    float share = 1;
    if (twoSided_) {
        share = 0.5f;
        if (uDir.x < 0.5f) {
            uDir.x = std::min(uDir.x * 2, 0x1.fffffep-1f);
        } else {
            uDir.x = std::min((uDir.x - 0.5f) * 2, 0x1.fffffep-1f);
            axis = -n;
        }
    }
    const float r = std::sqrt(uDir.x), phi = float(2 * Pi) * uDir.y;
    const float z = std::sqrt(std::max(0.f, 1 - uDir.x));
    if (!(z > 0)) return false;
    Vec3f s, t;
    CoordinateSystem(axis, &s, &t);
    const Vec3f w = Normalize(s * (r * std::cos(phi)) + t * (r * std::sin(phi)) + axis * z);
    ls->ray = Ray{p, w};
    ls->n = n;
    ls->Le = Le;
    ls->pdfPos = pdfPos;
    ls->pdfDir = share * z * float(InvPi);
    return true;
}

void DiffuseAreaLight::PdfLe(const Vec3f &, const Vec3f &n, const Vec3f &w, const SceneSphere &,
                             float *pdfPos, float *pdfDir) const {
    // Callers pass the point's triangle through PdfPosition; here the position density of an
    // analytic shape, or the mesh's by area (exact for untextured meshes).
    *pdfPos = analytic_ ? analytic_->PdfArea(n) : (meshArea_ > 0 ? float(1 / meshArea_) : 0.f);
    const float c = Dot(n, w);
    *pdfDir = twoSided_ ? 0.5f * std::abs(c) * float(InvPi) : std::max(c, 0.f) * float(InvPi);
}

double DiffuseAreaLight::Power(double) const {
    if (radiance_) {
        // Textured: the triangles' area × mean radiance (their sampling weights).
        double sum = 0;
        for (int i = 0; i < triangleWeights_.Count(); ++i) sum += triangleWeights_.Func(i);
        return (twoSided_ ? 2 : 1) * Pi * sum;
    }
    if (!triangleScale_.empty()) {
        double sum = 0;  // the triangles' area x scale
        for (size_t i = 0; i < triangleScale_.size(); ++i)
            sum += triangleAreas_[i] * triangleScale_[i];
        return (twoSided_ ? 2 : 1) * Pi * sum * Lemit_.Luminance();
    }
    const double area = analytic_ ? AnalyticArea() : meshArea_;
    return (twoSided_ ? 2 : 1) * Pi * area * Lemit_.Luminance();
}

double DiffuseAreaLight::AnalyticArea() const {
    // Uniform area sampling's object-space density, through the area Jacobian at one point
    // (exact for similarity transforms, an estimate otherwise: it only weighs choices).
    Vec3d p, n;
    double pdf;
    if (!analytic_->SampleObjectArea(Vec2f(0.5f, 0.5f), &p, &n, &pdf) || !(pdf > 0)) return 0;
    const Transform &m = analytic_->RenderFromObject();
    const double len = Length(n);
    const double jac =
        len > 0 ? std::abs(m.Matrix().Determinant3x3()) * Length(m.Normal(n / len)) : 1.0;
    return jac / pdf;
}

void DiffuseAreaLight::Bounds(std::vector<LightPartBounds> *parts) const {
    const float sides = twoSided_ ? 2.f : 1.f;
    if (analytic_) {
        // The shape's box, emitting in every direction (its normals span the sphere).
        LightPartBounds b;
        b.lb.bounds = analytic_->RenderBounds();
        b.lb.phi = float(Pi * AnalyticArea()) * sides * Lemit_.MaxComponent();
        b.lb.cosTheta_o = -1;
        b.lb.twoSided = twoSided_;
        parts->push_back(b);
        return;
    }
    if (!(meshArea_ > 0)) return;
    // Each triangle SampleLi can choose: its box, its normal, its power (area x radiance; a
    // textured triangle's sampling weight, area x mean radiance). A mesh of a few triangles
    // (a quad, a small lamp) is one part, the union of its triangles': choosing among them by
    // importance would cost the BVH's steps on every shadow ray for little gain; so is a
    // moving mesh.
    const size_t first = parts->size();
    for (int i = 0; i < triangleWeights_.Count(); ++i) {
        if (!(triangleWeights_.Func(i) > 0)) continue;
        const Vec3f n = mesh_->GeometricNormal(size_t(i));
        if (n == Vec3f(0, 0, 0)) continue;
        LightPartBounds b;
        b.prim = i;
        const uint32_t *v = mesh_->Triangle(size_t(i));
        b.lb.bounds = Bounds3f(mesh_->Position(v[0]), mesh_->Position(v[1]));
        b.lb.bounds.Expand(mesh_->Position(v[2]));
        b.lb.w = n;
        b.lb.cosTheta_o = 1;
        b.lb.twoSided = twoSided_;
        const double power = radiance_ ? triangleWeights_.Func(i)
                                       : triangleAreas_[size_t(i)] * Emitted(i).MaxComponent();
        b.lb.phi = float(Pi * power) * sides;
        parts->push_back(b);
    }
    const bool moving = mesh_->NumTimeSteps() > 1;
    if (!moving && parts->size() - first > size_t(MaxTrianglesChosenWhole)) return;
    LightPartBounds whole;
    for (size_t k = first; k < parts->size(); ++k) whole.lb = Union(whole.lb, (*parts)[k].lb);
    parts->resize(first);
    if (moving) {
        // A moving mesh (whose samples SampleLi takes where it starts, and rays meet anywhere
        // on its way): one part over every time step's vertices, emitting every way.
        for (int step = 1; step < mesh_->NumTimeSteps(); ++step) {
            const float *pos = mesh_->PositionData(step);
            for (size_t i = 0; i < mesh_->NumVertices(); ++i)
                whole.lb.bounds.Expand(Vec3f(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]));
        }
        whole.lb.cosTheta_o = -1;
    }
    if (whole.lb.phi > 0) parts->push_back(whole);
}

float DiffuseAreaLight::PdfLi(const SurfaceInteraction &ref, const Vec3f &wi,
                              const SurfaceInteraction *hit) const {
    if (!hit) return 0;
    if (analytic_) return analytic_->Pdf(ref.p, hit->p, hit->n);
    // SampleLi: a triangle by area (× mean radiance when textured), then a uniform point on
    // it: PdfArea, converted to solid angle.
    Vec3f w = hit->p - ref.p;
    float dist2 = LengthSquared(w);
    float cosLight = AbsDot(hit->n, wi);
    if (!(dist2 > 0) || cosLight == 0) return 0;
    return float(PdfArea(hit->prim) * dist2 / cosLight);
}

float DiffuseAreaLight::PdfLiTriangle(const SurfaceInteraction &ref, const Vec3f &wi,
                                      const SurfaceInteraction &hit) const {
    if (!mesh_ || hit.prim < 0 || size_t(hit.prim) >= triangleAreas_.size() ||
        !(triangleAreas_[size_t(hit.prim)] > 0))
        return 0;
    const float dist2 = LengthSquared(hit.p - ref.p);
    const float cosLight = AbsDot(hit.n, wi);
    if (!(dist2 > 0) || cosLight == 0) return 0;
    return float(dist2 / (cosLight * triangleAreas_[size_t(hit.prim)]));
}

}  // namespace prism
