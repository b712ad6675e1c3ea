// Analytic shapes (Embree user geometry): the interface shared by the quadrics and the torus.
// Positions are in render space (world space translated so the camera sits at the origin,
// render/render_scene.h), named as pbrt-v4 names them: renderFromObject, RenderBounds.
//
// Intersection is two-phase (the Mitsuba pattern): Intersect() runs inside Embree's callback
// and returns only the ray parameter and the object-space hit; Interaction() builds normals,
// uv and derivatives once, for the winning hit. Each shape implements one templated root
// routine IntersectT<Real>() that both the closest-hit and the occlusion callbacks use, with Real
// = double (default) or float (--precision float) so the cost of accuracy can be measured.
#pragma once

#include <memory>
#include <string>

#include "core/animated_transform.h"
#include "core/transform.h"
#include "core/vecmath.h"
#include "geometry/alpha.h"
#include "geometry/interaction.h"

namespace prism {

struct RevolutionProfile;  // tools/validate/tessellate.h

enum class Precision { Float, Double };

// Result of the root routine, in object space.
struct ObjectHit {
    double t = 0;    // ray parameter (units of the render-space ray's direction)
    Vec3d p;         // object-space hit point, re-projected onto the surface where possible
    Vec3d pError;    // conservative absolute error of p
    double phi = 0;  // azimuth of the hit (full spheres, cylinders and disks leave it 0:
                     // their Geometry computes it from p when uv is needed)
    // CSG (geometry/csg.h) only: the operand hit (SurfaceInteraction::instanceShape), its
    // triangle for a mesh operand, and whether its normal turns around (a carved surface).
    int part = -1, partPrim = 0;
    bool partFlip = false;
};

// A point sampled on a shape's surface for direct lighting, with the density of choosing it
// expressed in solid angle as seen from the reference point.
struct ShapeSample {
    Vec3f p, n;     // render-space point and unit normal (pbrt orientation, flips applied)
    float pdf = 0;  // solid-angle density at the reference point
};

// Object-space differential geometry at a hit.
struct LocalGeometry {
    Vec3d dpdu, dpdv;
    Vec3d n;  // unnormalized; pbrt orientation before ReverseOrientation/handedness flips
    Vec2d uv;
};

// 3x4 affine matrix in a chosen precision, for callbacks.
template <typename Real>
struct Affine3 {
    Real m[3][4];
    // Column sums of |m| (absCol[j] = sum_i |m[i][j]|, absCol[3] the translation's), so the
    // bound sum_ij |m_ij o_j| + sum_i |m_i3| on a transformed point's magnitude costs 3 products.
    Real absCol[4] = {0, 0, 0, 0};
    Vec3<Real> Point(const Vec3<Real> &p) const {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    Vec3<Real> Vector(const Vec3<Real> &v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
};

class AnalyticShape {
  public:
    AnalyticShape(const Transform &renderFromObject, bool reverseOrientation);
    virtual ~AnalyticShape() = default;

    virtual const char *Name() const = 0;
    virtual Bounds3d ObjectBounds() const = 0;
    // Implicit function F(p) (zero on the surface) and a bound on |grad F| scale, used by the
    // tests to measure residuals; positive outside for closed shapes.
    virtual double Implicit(const Vec3d &pObj) const = 0;
    virtual Vec3d ImplicitGradient(const Vec3d &pObj) const = 0;

    // Nearest valid hit with t in (tMin, tMax) for a render-space ray.
    virtual bool Intersect(const Vec3f &o, const Vec3f &d, float tMin, float tMax,
                           Precision precision, ObjectHit *hit) const = 0;
    // The same for a moving shape at a ray's time (Ray::time); Intersect if it does not move.
    virtual bool IntersectAt(const Vec3f &o, const Vec3f &d, float tMin, float tMax,
                             Precision precision, float time, ObjectHit *hit) const {
        return Intersect(o, d, tMin, tMax, precision, hit);
    }
    // Object-space differential geometry at a hit found by Intersect.
    virtual LocalGeometry Geometry(const ObjectHit &hit) const = 0;
    // The unnormalized object-space normal alone (Geometry(hit).n), for hits whose material
    // needs neither uv nor dpdu; shapes override it when that is cheaper.
    virtual Vec3d GeometricNormal(const ObjectHit &hit) const { return Geometry(hit).n; }

    // Curvature, asked only where a specular bounce carries ray differentials
    // (render/differentials.h): a smooth object-space vector field that lies along the surface
    // normal at every surface point (any length, either sign; ImplicitGradient by default), and
    // its directional derivative (Jacobian times dpObj, for dpObj tangent to the surface at
    // pObj). Closed forms per shape; zero for a plane.
    virtual Vec3d NormalField(const Vec3d &pObj) const { return ImplicitGradient(pObj); }
    virtual Vec3d NormalFieldDerivative(const Vec3d &pObj, const Vec3d &dpObj) const = 0;
    // The derivatives dn[i] of the render-space unit normal along the render-space tangent
    // vectors dp[i] (i < count) at the hit si on this shape: the Weingarten map, so dp = dpdu,
    // dpdv gives dndu, dndv and the footprint's dpdx, dpdy give dndx, dndy. Oriented as the
    // unit vector n (which lies in the normal's hemisphere: si.n or si.ns). Computed from the
    // shape at si.p (and si.time for a moving shape), so SurfaceInteraction carries none of it.
    virtual void NormalDerivatives(const SurfaceInteraction &si, const Vec3f &n, const Vec3f *dp,
                                   Vec3f *dn, int count) const;

    // Uniform sampling of the object-space surface by area: the point, its unnormalized
    // normal (pbrt orientation before flips) and the object-space area density. Shapes that
    // cannot be sampled return false (they cannot be area lights).
    virtual bool SampleObjectArea(Vec2f u, Vec3d *p, Vec3d *n, double *pdfArea) const {
        return false;
    }
    // Samples a point for direct lighting of `ref`, with the solid-angle density. The default
    // converts object-space area sampling through the transform's exact area Jacobian.
    virtual bool Sample(const Vec3f &ref, Vec2f u, ShapeSample *ss) const;
    // The solid-angle density with which Sample(ref, ...) gives the surface point p (unit
    // normal n, render space), e.g. a point a ray from ref hit: multiple importance sampling.
    virtual float Pdf(const Vec3f &ref, const Vec3f &p, const Vec3f &n) const;
    // Uniform area sampling in render space (light tracing): the point, its unit normal and
    // ss->pdf the density per unit render-space area; PdfArea is that density at a point with
    // unit normal n (it depends on n alone, through the area Jacobian).
    bool SampleArea(Vec2f u, ShapeSample *ss) const;
    float PdfArea(const Vec3f &n) const;
    bool CanSample() const {
        Vec3d p, n;
        double pdf;
        return SampleObjectArea(Vec2f(0.5f, 0.5f), &p, &n, &pdf);
    }

    // [validate hook] Every analytic shape is a profile curve swept about z; shapes fill in
    // that description (in each shape's own .cpp; geometry/revolution.h) for tessellation and
    // `prism validate`.
    // Returns false for shapes that cannot describe themselves so.
    virtual bool Revolution(RevolutionProfile *profile) const { return false; }

    // Render-space bounds, padded by a relative margin: Embree's user-geometry traversal is not
    // robust (docs/SHAPES.md E2), so the box must absorb its rounding.
    Bounds3f RenderBounds() const;
    // Phase 2: the full render-space interaction for a hit.
    // `needs` (SurfaceNeeds) says whether uv and dpdu/dpdv are computed; the rest always is.
    // `time` (Ray::time) matters only for a moving shape; it, `shape` and `prim` (the render
    // scene's indices) are stored in the result, so that Accel returns it as built.
    SurfaceInteraction Interaction(const ObjectHit &hit, const Vec3f &rayDir,
                                   unsigned needs = NeedAll, float time = 0, int shape = -1,
                                   int prim = 0) const;

    // Motion blur: the render-from-object transform over the shutter, its times fractions of
    // the shutter interval (0 at shutteropen, 1 at shutterclose; Ray::time), its value at time
    // 0 the transform the shape was made with. Set before the shape is attached; a shape
    // without motion (the default) pays nothing. Embree time steps then carry bounds that
    // cover the motion, and the callbacks interpolate the transform at each ray's time.
    void SetMotion(const AnimatedTransform &renderFromObject);
    const AnimatedTransform *Motion() const { return motion_.get(); }
    int MotionTimeSteps() const { return motionSteps_; }
    // Render-space bounds around the shape over the time step's share of the motion (steps
    // MotionTimeSteps(), evenly spaced over [0, 1]), padded as RenderBounds.
    Bounds3f RenderBoundsAtStep(int step) const;
    // objectFromRender at a ray's time (moving shapes).
    template <typename Real>
    Affine3<Real> ObjectFromRenderAt(float time) const;

    const Transform &RenderFromObject() const { return renderFromObject_; }
    bool FlipNormals() const { return flipNormals_; }
    // Cut-outs (geometry/alpha.h), tested by the user-geometry callbacks; set before the
    // shape is attached. Without them (the default) the callbacks test nothing.
    void SetAlpha(ShapeAlpha alpha) { alpha_ = std::move(alpha); }
    const ShapeAlpha &Alpha() const { return alpha_; }

    template <typename Real>
    const Affine3<Real> &ObjectFromRender() const {
        if constexpr (std::is_same_v<Real, float>)
            return objectFromRenderF_;
        else
            return objectFromRenderD_;
    }

  protected:
    ShapeAlpha alpha_;
    std::shared_ptr<const AnimatedTransform> motion_;
    int motionSteps_ = 1;
    bool motionLinearBounds_ = false;  // per-step boxes interpolate exactly (no rotation, kinks)
    Transform renderFromObject_;
    bool reverseOrientation_, flipNormals_;
    Affine3<float> objectFromRenderF_;
    Affine3<double> objectFromRenderD_;
};

// Adds the per-shape render-space ray → object-ray conversion and the precision switch on top of a
// shape's templated root routine: Derived provides
//   template <typename Real> bool IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax,
//                                            Real tSlack, ObjectHit *hit) const;
// where tSlack bounds the error in t caused by rounding in the render-to-object transform of
// the ray origin (negligible in double, decisive in float for far-from-origin shapes).
template <typename Derived>
class AnalyticShapeT : public AnalyticShape {
  public:
    using AnalyticShape::AnalyticShape;

    template <typename Real>
    bool IntersectRender(const Vec3f &o, const Vec3f &d, float tMin, float tMax,
                         ObjectHit *hit) const {
        return IntersectRenderWith<Real>(ObjectFromRender<Real>(), o, d, tMin, tMax, hit);
    }
    // With a given objectFromRender (a moving shape's at the ray's time).
    template <typename Real>
    bool IntersectRenderWith(const Affine3<Real> &m, const Vec3f &o, const Vec3f &d, float tMin,
                             float tMax, ObjectHit *hit) const {
        Vec3<Real> ow(o), dw(d);
        Vec3<Real> oo = m.Point(ow), dd = m.Vector(dw);
        // pbrt-v3 transform.h: |error| <= gamma3 (|M| |o| + |t|) per component.
        Real oErr = m.absCol[0] * std::abs(ow.x) + m.absCol[1] * std::abs(ow.y) +
                    m.absCol[2] * std::abs(ow.z) + m.absCol[3];
        Real dLen = Length(dd);
        Real tSlack = dLen > 0 ? Gamma<Real>(3) * oErr / dLen : Real(0);
        return static_cast<const Derived *>(this)->template IntersectT<Real>(
            oo, dd, Real(tMin), Real(tMax), tSlack, hit);
    }
    bool Intersect(const Vec3f &o, const Vec3f &d, float tMin, float tMax, Precision precision,
                   ObjectHit *hit) const override {
        return precision == Precision::Double ? IntersectRender<double>(o, d, tMin, tMax, hit)
                                              : IntersectRender<float>(o, d, tMin, tMax, hit);
    }
    bool IntersectAt(const Vec3f &o, const Vec3f &d, float tMin, float tMax, Precision precision,
                     float time, ObjectHit *hit) const override {
        if (!motion_) return Intersect(o, d, tMin, tMax, precision, hit);
        return precision == Precision::Double
                   ? IntersectRenderWith<double>(ObjectFromRenderAt<double>(time), o, d, tMin, tMax,
                                                 hit)
                   : IntersectRenderWith<float>(ObjectFromRenderAt<float>(time), o, d, tMin, tMax,
                                                hit);
    }
};

}  // namespace prism
