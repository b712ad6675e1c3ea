#include "geometry/shape.h"

#include <cmath>
#include <optional>

namespace prism {

static Bounds3f PaddedBounds(const Bounds3d &b);

template <typename Real>
static Affine3<Real> ToAffine(const Matrix4 &m) {
    Affine3<Real> a;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) a.m[i][j] = Real(m.m[i][j]);
    for (int j = 0; j < 4; ++j)
        a.absCol[j] = std::abs(a.m[0][j]) + std::abs(a.m[1][j]) + std::abs(a.m[2][j]);
    return a;
}

AnalyticShape::AnalyticShape(const Transform &renderFromObject, bool reverseOrientation)
    : renderFromObject_(renderFromObject),
      reverseOrientation_(reverseOrientation),
      flipNormals_(reverseOrientation != renderFromObject.SwapsHandedness()),
      objectFromRenderF_(ToAffine<float>(renderFromObject.InverseMatrix())),
      objectFromRenderD_(ToAffine<double>(renderFromObject.InverseMatrix())) {}

Bounds3f AnalyticShape::RenderBounds() const {
    return PaddedBounds(renderFromObject_.Bounds(ObjectBounds()));
}

void AnalyticShape::SetMotion(const AnimatedTransform &renderFromObject) {
    motion_ = std::make_shared<const AnimatedTransform>(renderFromObject);
    motionSteps_ = prism::MotionTimeSteps(renderFromObject, &motionLinearBounds_);
}

Bounds3f AnalyticShape::RenderBoundsAtStep(int step) const {
    if (!motion_ || motionSteps_ < 2) return RenderBounds();
    double dt = 1.0 / (motionSteps_ - 1), t = step * dt;
    // Linear motion: the boxes at the steps, which Embree's interpolation between them
    // covers exactly. Otherwise each step's box covers the motion over the segments on both
    // sides, so the interpolation of two neighbours holds their shared segment.
    if (motionLinearBounds_) return PaddedBounds(motion_->Interpolate(t).Bounds(ObjectBounds()));
    return PaddedBounds(motion_->MotionBounds(ObjectBounds(), t - dt, t + dt));
}

template <typename Real>
Affine3<Real> AnalyticShape::ObjectFromRenderAt(float time) const {
    return ToAffine<Real>(motion_->InterpolateInverseMatrix(double(time)));
}
template Affine3<float> AnalyticShape::ObjectFromRenderAt<float>(float) const;
template Affine3<double> AnalyticShape::ObjectFromRenderAt<double>(float) const;

static Bounds3f PaddedBounds(const Bounds3d &b) {
    // Relative padding: 1e-6 of the largest coordinate magnitude plus the box's own extent,
    // then rounded outward to float.
    double scale = std::max(MaxComponent(Abs(b.pMin)), MaxComponent(Abs(b.pMax)));
    double pad = 1e-6 * scale + 1e-6 * MaxComponent(b.Diagonal()) + 1e-30;
    Bounds3f r;
    for (int i = 0; i < 3; ++i) {
        r.pMin[i] = NextFloatDown(float(b.pMin[i] - pad));
        r.pMax[i] = NextFloatUp(float(b.pMax[i] + pad));
    }
    return r;
}

bool AnalyticShape::Sample(const Vec3f &ref, Vec2f u, ShapeSample *ss) const {
    Vec3d pObj, nObj;
    double pdfObj;
    if (!SampleObjectArea(u, &pObj, &nObj, &pdfObj)) return false;
    double nLen = Length(nObj);
    if (!(nLen > 0) || !(pdfObj > 0)) return false;
    // World area element: dA_w = |det M| |M^-T n_o| dA_o for a unit object normal n_o.
    Vec3d nW = renderFromObject_.Normal(nObj / nLen);
    double jac = std::abs(renderFromObject_.Matrix().Determinant3x3()) * Length(nW);
    Vec3d pW = renderFromObject_.Point(pObj);
    nW = Normalize(nW);
    if (flipNormals_) nW = -nW;
    Vec3d w = pW - Vec3d(ref);
    double dist2 = LengthSquared(w);
    if (!(dist2 > 0)) return false;
    double cosLight = std::abs(Dot(nW, w)) / std::sqrt(dist2);
    if (cosLight == 0) return false;
    ss->p = Vec3f(pW);
    ss->n = Vec3f(nW);
    ss->pdf = float(pdfObj / jac * dist2 / cosLight);
    return std::isfinite(ss->pdf) && ss->pdf > 0;
}

bool AnalyticShape::SampleArea(Vec2f u, ShapeSample *ss) const {
    Vec3d pObj, nObj;
    double pdfObj;
    if (!SampleObjectArea(u, &pObj, &nObj, &pdfObj)) return false;
    const double nLen = Length(nObj);
    if (!(nLen > 0) || !(pdfObj > 0)) return false;
    Vec3d nW = renderFromObject_.Normal(nObj / nLen);
    const double jac = std::abs(renderFromObject_.Matrix().Determinant3x3()) * Length(nW);
    nW = Normalize(nW);
    if (flipNormals_) nW = -nW;
    ss->p = Vec3f(renderFromObject_.Point(pObj));
    ss->n = Vec3f(nW);
    ss->pdf = float(pdfObj / jac);
    return std::isfinite(ss->pdf) && ss->pdf > 0;
}

float AnalyticShape::PdfArea(const Vec3f &n) const {
    Vec3d pObj, nObj;
    double pdfObj;
    if (!SampleObjectArea(Vec2f(0.5f, 0.5f), &pObj, &nObj, &pdfObj) || !(pdfObj > 0)) return 0;
    const Vec3d nO = renderFromObject_.Inverse().Normal(Vec3d(n));
    const double lenO = Length(nO);
    if (!(lenO > 0)) return 0;
    const double jac = std::abs(renderFromObject_.Matrix().Determinant3x3()) *
                       Length(renderFromObject_.Normal(nO / lenO));
    const double pdf = pdfObj / jac;
    return std::isfinite(pdf) ? float(pdf) : 0.f;
}

float AnalyticShape::Pdf(const Vec3f &ref, const Vec3f &p, const Vec3f &n) const {
    // Uniform area sampling: the object-space density (one value for the whole surface)
    // through the area Jacobian at p's normal, then to solid angle at ref.
    Vec3d pObj, nObj;
    double pdfObj;
    if (!SampleObjectArea(Vec2f(0.5f, 0.5f), &pObj, &nObj, &pdfObj) || !(pdfObj > 0)) return 0;
    Vec3d nO = renderFromObject_.Inverse().Normal(Vec3d(n));
    double lenO = Length(nO);
    if (!(lenO > 0)) return 0;
    double jac = std::abs(renderFromObject_.Matrix().Determinant3x3()) *
                 Length(renderFromObject_.Normal(nO / lenO));
    Vec3d w = Vec3d(p) - Vec3d(ref);
    double dist2 = LengthSquared(w);
    double cosLight = std::abs(Dot(Vec3d(n), w)) / std::sqrt(dist2);
    if (!(dist2 > 0) || cosLight == 0) return 0;
    double pdf = pdfObj / jac * dist2 / cosLight;
    return std::isfinite(pdf) ? float(pdf) : 0.f;
}

namespace {

// AnalyticShape::Interaction with the render-from-object transform at the ray's time. The
// result is built once, at the end, in the caller's object (a SurfaceInteraction declared up
// front is zero-filled first, 144 bytes per hit, as is a LocalGeometry).
SurfaceInteraction ShapeInteraction(const AnalyticShape &shape, const Transform &rfo,
                                    const ObjectHit &hit, const Vec3f &rayDir, unsigned needs,
                                    float time, int shapeIndex, int prim, bool flip) {
    Vec3d gn;
    Vec3f dpdu, dpdv;
    Vec2f uv;
    if (needs == NeedNone) {
        gn = shape.GeometricNormal(hit);
    } else {
        const LocalGeometry g = shape.Geometry(hit);
        gn = g.n;
        if (needs & NeedDpdu) {
            dpdu = Vec3f(rfo.Vector(g.dpdu));
            dpdv = Vec3f(rfo.Vector(g.dpdv));
        }
        if (needs & NeedUV) uv = Vec2f(float(g.uv.x), float(g.uv.y));
    }
    const Vec3d pW = rfo.Point(hit.p);
    const Vec3d errW = rfo.PointError(hit.p, hit.pError, MachineEpsilon<double>());
    Vec3f p, pError;
    RoundHitPoint(pW, errW, &p, &pError);
    Vec3d n = Normalize(rfo.Normal(gn));
    if (flip) n = -n;
    return SurfaceInteraction{.p = p,
                              .pError = pError,
                              .n = Vec3f(n),
                              .ns = Vec3f(n),
                              .dpdu = dpdu,
                              .dpdv = dpdv,
                              .uv = uv,
                              .uv1 = uv,
                              .wo = Normalize(-rayDir),
                              .t = float(hit.t),
                              .shape = shapeIndex,
                              .prim = prim,
                              .instanceShape = hit.part,  // -1 except for CSG operands
                              .time = time};
}

}  // namespace

void AnalyticShape::NormalDerivatives(const SurfaceInteraction &si, const Vec3f &n, const Vec3f *dp,
                                      Vec3f *dn, int count) const {
    // With N the object-space field, the render-space unit normal is m = M^-T N / |M^-T N|
    // (M = renderFromObject), so along a render-space dp (object dpObj = M^-1 dp)
    // dm = (I - m m^T) M^-T dN / |M^-T N| with dN = NormalFieldDerivative(pObj, dpObj).
    // Everything goes through objectFromRender (M^-1): M^-T v is its transpose times v.
    Affine3<double> moved;
    const Affine3<double> &ofr =
        motion_ ? (moved = ObjectFromRenderAt<double>(si.time)) : objectFromRenderD_;
    auto inverseTranspose = [&ofr](const Vec3d &v) {
        const auto &m = ofr.m;
        return Vec3d(m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z,
                     m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
                     m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z);
    };
    const Vec3d pObj = ofr.Point(Vec3d(si.p));
    const Vec3d mW = inverseTranspose(NormalField(pObj));
    const double len = Length(mW);
    if (!(len > 0) || !std::isfinite(len)) {
        for (int i = 0; i < count; ++i) dn[i] = Vec3f();
        return;
    }
    const Vec3d m = mW / len;
    const double scale = (Dot(m, Vec3d(n)) < 0 ? -1 : 1) / len;
    for (int i = 0; i < count; ++i) {
        const Vec3d dN = inverseTranspose(NormalFieldDerivative(pObj, ofr.Vector(Vec3d(dp[i]))));
        dn[i] = Vec3f((dN - m * Dot(m, dN)) * scale);
    }
}

SurfaceInteraction AnalyticShape::Interaction(const ObjectHit &hit, const Vec3f &rayDir,
                                              unsigned needs, float time, int shape,
                                              int prim) const {
    if (motion_)
        return ShapeInteraction(*this, motion_->Interpolate(double(time)), hit, rayDir, needs, time,
                                shape, prim, flipNormals_);
    return ShapeInteraction(*this, renderFromObject_, hit, rayDir, needs, time, shape, prim,
                            flipNormals_);
}

}  // namespace prism
