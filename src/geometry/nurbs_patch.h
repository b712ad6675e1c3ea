// NURBS surface patches (pbrt-v3's Shape "nurbs"): the B-spline basis by the Cox-de Boor
// recurrence, the rational surface and its first derivatives, and an adaptive tessellation
// into a triangle mesh with per-vertex normals and the parametric (u, v) as uv.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/vecmath.h"

namespace prism {

// Upper bounds on what a patch may ask for; ValidateNurbs rejects more.
inline constexpr int MaxNurbsOrder = 64;
inline constexpr uint64_t MaxNurbsTriangles = uint64_t(1) << 21;

// A bad nurbs or heightfield parameter: `param` names it (pbrt's name: "nu", "uknots", "Pw", ...)
// so the caller can report the message at that parameter's location.
class PatchParamError : public std::invalid_argument {
  public:
    PatchParamError(const char *param, const std::string &message)
        : std::invalid_argument(message), param(param) {}
    const char *param;
};

// One patch. Control point (i, j), i < nu along u, j < nv along v, is Pw[4 (j nu + i) ...]:
// homogeneous (w x, w y, w z, w), as pbrt-v3's "float Pw" (a non-rational "point P" has w = 1).
// Knot vectors have nu + uorder and nv + vorder values; the patch covers [u0, u1] x [v0, v1],
// which must lie in the knots' domain [uknots[uorder-1], uknots[nu]] (likewise for v).
struct NurbsPatch {
    int nu = 0, nv = 0, uorder = 0, vorder = 0;
    std::vector<double> uknots, vknots;
    std::vector<double> Pw;
    double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
};

// Throws PatchParamError for: counts below 1 or whose product overflows, orders outside
// 2..min(count, MaxNurbsOrder), knot vectors of the wrong length, decreasing or not finite,
// an empty domain, a parameter range that is empty or leaves the domain, control points not
// nu * nv, not finite, or with weight w <= 0.
void ValidateNurbs(const NurbsPatch &patch);

// The knot span i (order-1 <= i <= count-1, knots[i] < knots[i+1]) that holds t: with
// knots[i] <= t < knots[i+1], or, `fromLeft`, knots[i] < t <= knots[i+1] (the limit from
// below, for one-sided derivatives at a knot). t outside the domain takes the end span.
int FindKnotSpan(const std::vector<double> &knots, int count, int order, double t, bool fromLeft);
// The order non-zero basis functions N[j] = N_{span-order+1+j} at t in span `span`, and their
// derivatives dN[j] (dN may be null). N and dN hold `order` values.
void BSplineBasis(const std::vector<double> &knots, int order, int span, double t, double *N,
                  double *dN);

struct NurbsPoint {
    Vec3d P, dPdu, dPdv;
};
// The surface point and its partial derivatives at (u, v), one-sided from below in u or v
// when asked (at a knot where the surface has a crease). The patch must be valid.
NurbsPoint EvaluateNurbs(const NurbsPatch &patch, double u, double v, bool uFromLeft = false,
                         bool vFromLeft = false);

// The tessellation rule: every distinct knot inside the range is a grid line; each knot span
// gets at least its share of `minSegments` segments (pbrt-v3's fixed 30 x 30 grid is 29 x 29
// segments) and is split further until the chordal error, measured at the middle of every grid
// edge and at the centre of every cell (against the triangles' diagonal), is at most
// `relativeTolerance` times the diagonal of the patch's bounding box, or until the mesh would
// exceed `maxTriangles`. Across a knot where the surface is only C0 (multiplicity >= order-1)
// the grid line is doubled, so both sides keep their own normals; the positions are shared
// (knot multiplicity >= order: the surface itself breaks there, and so does the mesh).
struct NurbsTessellationOptions {
    int minSegments = 29;
    double relativeTolerance = 2e-4;
    uint64_t maxTriangles = MaxNurbsTriangles;
};

struct PatchMesh {
    std::vector<Vec3f> P, N;   // object space; N unit, facing dP/du x dP/dv
    std::vector<Vec2f> uv;     // the parametric (u, v)
    std::vector<int> indices;  // 3 per triangle, wound so (p1-p0) x (p2-p0) faces N
};

struct NurbsTessellation {
    PatchMesh mesh;
    int segmentsU = 0, segmentsV = 0;  // grid segments along u and v
    double chordalError = 0;           // the largest error measured, object-space units
    double tolerance = 0;              // the error asked for, object-space units
    bool capped = false;               // stopped by maxTriangles before reaching tolerance
};

// The triangles of the smallest grid the rule allows (knot spans and minSegments alone), to
// check against limits before tessellating.
uint64_t MinNurbsTriangles(const NurbsPatch &patch, int minSegments = 29);

// Tessellates a valid patch. Throws PatchParamError("nu") if even the smallest grid would
// exceed maxTriangles.
NurbsTessellation TessellateNurbs(const NurbsPatch &patch,
                                  const NurbsTessellationOptions &options = {});

}  // namespace prism
