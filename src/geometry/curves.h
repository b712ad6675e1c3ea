// pbrt-v3's "curve" shape as Embree's native curves: every basis and degree pbrt-v3 reads
// becomes cubic Bézier segments (exactly), traced as RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE
// ("flat": a ribbon facing each ray), ROUND_BEZIER_CURVE ("cylinder": a swept tube) or
// NORMAL_ORIENTED_BEZIER_CURVE ("ribbon": a band turned by the normals "N").
#pragma once

#include <cstdint>
#include <vector>

#include "core/transform.h"
#include "geometry/interaction.h"

namespace prism {

enum class CurveType { Flat, Cylinder, Ribbon };

// The most segments one curve shape may have (Embree's 32-bit indices address 4 control
// points a segment; the memory budget usually stops a file long before).
inline constexpr size_t MaxCurveSegments = size_t(1) << 28;

// The most ray-facing quads per flat segment (rtcSetGeometryTessellationRate; Embree's
// default is 4). of ray-facing quads per flat segment (rtcSetGeometryTessellationRate).
inline constexpr int MaxCurveTessellation = 64;

// The number of segments a pbrt-v3 curve of `points` control points makes: degree*n + 1
// points for the Bézier basis, n + degree for the B-spline basis; 0 when no whole number of
// segments fits (at least one segment is needed). `degree` must be 2 or 3.
size_t CurveSegmentCount(size_t points, int degree, bool bspline);

// The curve's cubic Bézier control points, 4 per segment (segment i from 4i): cubic Bézier
// segments as given, B-spline segments converted to Bézier form and quadratic segments
// elevated to cubic, all exactly (up to float rounding). Throws std::invalid_argument when
// CurveSegmentCount is 0 or the degree is not 2 or 3.
std::vector<Vec3f> CubicBezierSegments(const std::vector<Vec3f> &P, int degree, bool bspline);

// The cubic Bézier value and derivative at u of 4 control points.
template <typename V>
inline V BezierPoint(const V *c, double u) {
    const double s = 1 - u;
    return c[0] * (s * s * s) + c[1] * (3 * s * s * u) + c[2] * (3 * s * u * u) +
           c[3] * (u * u * u);
}
template <typename V>
inline V BezierDerivative(const V *c, double u) {
    const double s = 1 - u;
    return (c[1] - c[0]) * (3 * s * s) + (c[2] - c[1]) * (6 * s * u) + (c[3] - c[2]) * (3 * u * u);
}

// One pbrt "curve" shape in render space: its segments, their radii and (ribbons) normals,
// shared with Embree without copying.
class CurveSet {
  public:
    // `bezier`: object-space cubic Bézier control points, 4 per segment (CubicBezierSegments).
    // The width runs linearly from width0 at the curve's start to width1 at its end (pbrt-v3),
    // each segment covering an equal part of the curve's u; Embree's per-control-point radius
    // is that width / 2 at the control point's parameter (a linear function has Bézier
    // coefficients equal to its values at u = 0, 1/3, 2/3, 1, so the radius is exactly
    // linear), scaled by the transform's scale (the cube root of |det|, exact for uniform
    // scales). `N` (ribbons): one object-space normal per segment end (segments + 1); between
    // two ends the normal turns along the great circle from one to the other (pbrt-v3's
    // spherical interpolation), given to Embree as the cubic Bézier arc approximation.
    // Throws std::invalid_argument for inconsistent sizes.
    CurveSet(const Transform &renderFromObject, bool reverseOrientation, CurveType type,
             const std::vector<Vec3f> &bezier, float width0, float width1,
             const std::vector<Vec3f> &N = {}, int tessellationRate = 4);

    // The bytes a set of this many segments holds (float4 control points, indices, normals).
    static uint64_t Bytes(uint64_t segments, bool normals) {
        return segments * (4 * 4 * sizeof(float) + sizeof(uint32_t)) +
               (normals ? segments * 4 * 3 * sizeof(float) + sizeof(float) : 0);
    }

    CurveType Type() const { return type_; }
    size_t NumSegments() const { return indices_.size(); }
    size_t NumVertices() const { return 4 * indices_.size(); }
    // Embree's buffers at time step `step`: x y z r and (ribbons) x y z, 4 per segment.
    const float *VertexData(int step = 0) const {
        return step == 0 ? vertices_.data() : stepVertices_[size_t(step - 1)].data();
    }
    const float *NormalData(int step = 0) const {
        return step == 0 ? normals_.data() : stepNormals_[size_t(step - 1)].data();
    }
    const uint32_t *IndexData() const { return indices_.data(); }
    uint64_t MemoryBytes() const {
        return Bytes(NumSegments(), !normals_.empty()) * uint64_t(NumTimeSteps());
    }
    // Motion blur (Embree time steps), as TriangleMesh::SetMotionSteps: the curves moved by
    // each transform (render space to render space), one per step after the first, evenly
    // over the shutter; radii scale with each transform's scale. Between steps Embree moves
    // the control points, radii and normals linearly, and Interaction follows it.
    void SetMotionSteps(const std::vector<Transform> &stepFromStart);
    int NumTimeSteps() const { return 1 + int(stepVertices_.size()); }
    int TessellationRate() const { return tessellationRate_; }
    Bounds3f RenderBounds() const;

    // Segment `prim` at `time`: its 4 control points, radii and (ribbons) normals.
    struct Segment {
        Vec3d p[4];
        double r[4];
        Vec3d n[4];
        // The centre, the tangent (d/du of the whole curve's u, over `segments`) and the
        // radius at the segment's parameter u.
        Vec3d Center(double u) const { return BezierPoint(p, u); }
        Vec3d Tangent(double u, size_t segments) const {
            return BezierDerivative(p, u) * double(segments);
        }
        double Radius(double u) const;
    };
    Segment SegmentAt(size_t prim, float time = 0) const;

    // Phase 2 for Embree's hit (segment `prim`, its parameter u and v) at t along the ray.
    // uv follows pbrt-v3: u along the whole curve (0 to 1 over all segments), v across it (0
    // to 1, 0.5 on the centre line, as the ray sees the width). n: "flat" faces the ray,
    // "cylinder" is pbrt's normal turned across the band (its hit on the plane through the
    // centre line, with a bound that starts every leaving ray outside the tube), "ribbon" the
    // interpolated "N" made perpendicular to the curve; flipped by ReverseOrientation XOR
    // handedness, as pbrt does.
    SurfaceInteraction Interaction(size_t prim, float u, float v, float t, const Vec3f &rayO,
                                   const Vec3f &rayD, float time = 0, int shape = -1) const;

  private:
    CurveType type_;
    bool flipNormals_;
    int tessellationRate_;
    std::vector<float> vertices_;  // padded by one float4 (Embree reads past the last)
    std::vector<uint32_t> indices_;
    std::vector<float> normals_;                                  // padded by one float
    std::vector<std::vector<float>> stepVertices_, stepNormals_;  // motion steps 1..n-1
};

}  // namespace prism
