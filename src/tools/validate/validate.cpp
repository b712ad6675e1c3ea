#include "tools/validate/validate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/rng.h"
#include "geometry/accel.h"
#include "geometry/shape_list.h"
#include "geometry/sphere.h"
#include "tools/validate/tessellate.h"

namespace prism {

namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

double AngleDeg(const Vec3f &a, const Vec3f &b) {
    Vec3d x(a), y(b);
    double la = Length(x), lb = Length(y);
    if (!(la > 0) || !(lb > 0)) return 180;
    // atan2 of |cross| and dot: accurate for small angles, unlike acos.
    return Degrees(std::atan2(Length(Cross(x, y)), Dot(x, y)));
}

double UlpF(double t) {
    float f = float(std::abs(t));
    return double(std::nextafter(f, Infinity)) - double(f);
}

// Norm bound of the linear part of objectFromWorld (Frobenius), to carry world-space float
// rounding into object space.
double InverseScale(const Transform &renderFromObject) {
    const Matrix4 &mi = renderFromObject.InverseMatrix();
    double s = 0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) s += mi.m[r][c] * mi.m[r][c];
    return std::sqrt(s);
}

// Object-space ray segment inside the (padded) object bounds.
bool ClipToBounds(const Bounds3d &b, const Vec3d &o, const Vec3d &d, double *t0, double *t1) {
    double lo = 0, hi = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0) {
            if (o[i] < b.pMin[i] || o[i] > b.pMax[i]) return false;
            continue;
        }
        double a = (b.pMin[i] - o[i]) / d[i], c = (b.pMax[i] - o[i]) / d[i];
        if (a > c) std::swap(a, c);
        lo = std::max(lo, a);
        hi = std::min(hi, c);
    }
    *t0 = lo;
    *t1 = hi;
    return lo <= hi;
}

// Least squares slope of y against x.
double Slope(const std::vector<double> &x, const std::vector<double> &y, double *intercept) {
    size_t n = x.size();
    double mx = 0, my = 0;
    for (size_t i = 0; i < n; ++i) {
        mx += x[i];
        my += y[i];
    }
    mx /= double(n);
    my /= double(n);
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < n; ++i) {
        sxy += (x[i] - mx) * (y[i] - my);
        sxx += (x[i] - mx) * (x[i] - mx);
    }
    double s = sxx > 0 ? sxy / sxx : 0;
    if (intercept) *intercept = my - s * mx;
    return s;
}

// Closest-hit queries for the whole ray set, one thread, rtcIntersect1. The machine is
// shared and noisy: the pass is repeated and the fastest repetition is the time per ray.
double TimedPass(const Accel &accel, const std::vector<Ray> &rays, std::vector<char> *hit,
                 std::vector<RawHit> *raw) {
    const int reps = 5;
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < reps; ++k) {
        auto t0 = Clock::now();
        for (size_t i = 0; i < rays.size(); ++i)
            (*hit)[i] = accel.IntersectRaw(rays[i], &(*raw)[i]);
        best = std::min(best, Seconds(t0));
    }
    return best * 1e9 / double(std::max<size_t>(rays.size(), 1));
}

struct AnalyticRay {
    bool hit = false;
    float t = 0;
    Vec3f n;            // world geometric normal
    double tBound = 0;  // per-ray unit of the dt bound: 1 / (|d_obj| |cos theta|)
    double tErr = 0;    // analytic t error bound from pError
};

}  // namespace

int64_t ShapeReport::OutOfBand() const {
    int64_t n = 0;
    for (const LevelStats &l : levels) n += l.outOfBand;
    return n;
}

int64_t ShapeReport::Leaks() const {
    int64_t n = 0;
    for (const LevelStats &l : levels) n += l.leaks;
    return n;
}

std::vector<Ray> RandomRaysAt(const AnalyticShape &shape, int count, uint64_t seed) {
    Bounds3f b = shape.RenderBounds();
    Vec3d lo(b.pMin), hi(b.pMax);
    double diag = Length(hi - lo);
    PCG32 rng(seed, 0x5eedULL);
    std::vector<Ray> rays;
    rays.reserve(size_t(std::max(count, 0)));
    for (int i = 0; i < count; ++i) {
        Vec3d target(Lerp(rng.UniformDouble(), lo.x, hi.x), Lerp(rng.UniformDouble(), lo.y, hi.y),
                     Lerp(rng.UniformDouble(), lo.z, hi.z));
        double z = 1 - 2 * rng.UniformDouble(), phi = 2 * Pi * rng.UniformDouble();
        double s = SafeSqrt(1 - z * z);
        Vec3d dir(s * std::cos(phi), s * std::sin(phi), z);
        // Start a full diagonal away: outside the bounds' circumsphere, so outside the shape.
        Vec3d o = target - dir * diag;
        Ray r;
        r.o = Vec3f(o);
        r.d = Vec3f(dir);
        rays.push_back(r);
    }
    return rays;
}

ShapeReport ValidateShape(const std::string &name, std::unique_ptr<AnalyticShape> shapePtr,
                          const std::vector<Ray> &extraRays, const ValidateOptions &options) {
    ShapeReport rep;
    rep.name = name;
    AccelOptions aOpt;
    aOpt.precision = options.precision;
    Accel analytic(aOpt);
    analytic.AddAnalytic(std::move(shapePtr));
    analytic.Commit();
    const AnalyticShape &shape = *analytic.Analytic(0);
    RevolutionProfile profile;
    if (!shape.Revolution(&profile)) {
        rep.note = "no tessellation for this shape; skipped";
        return rep;
    }
    std::vector<Ray> rays = RandomRaysAt(shape, options.rays, options.seed);
    rays.insert(rays.end(), extraRays.begin(), extraRays.end());
    size_t nr = rays.size();
    rep.rays = int64_t(nr);

    // ---- The analytic side: timed pass, then the per-hit geometry the checks need.
    std::vector<AnalyticRay> ar(nr);
    std::vector<RawHit> rawA(nr);
    std::vector<char> hitA(nr);
    rep.nsPerRayAnalytic = TimedPass(analytic, rays, &hitA, &rawA);
    Transform objFromWorld = shape.RenderFromObject().Inverse();
    double errSum = 0;
    for (size_t i = 0; i < nr; ++i) {
        if (!hitA[i]) continue;
        AnalyticRay &a = ar[i];
        a.hit = true;
        a.t = rawA[i].t;
        SurfaceInteraction si = analytic.Interaction(rays[i], rawA[i]);
        a.n = si.n;
        double dl = Length(Vec3d(rays[i].d));
        a.tErr = Length(Vec3d(si.pError)) / dl;
        errSum += a.tErr;
        ++rep.analyticHits;
        // Incidence in object space, where the chord error is measured (the transform may
        // scale non-uniformly): the bound on dt is h / (|d_obj| |cos theta_obj|).
        Vec3d dObj = objFromWorld.Vector(Vec3d(rays[i].d));
        ObjectHit oh;
        Vec3d nObj;
        if (shape.Intersect(rays[i].o, rays[i].d, rays[i].tMin, rays[i].tMax, Precision::Double,
                            &oh))
            nObj = shape.Geometry(oh).n;
        else
            nObj = objFromWorld.Normal(Vec3d(si.n));
        double c = std::abs(Dot(dObj, nObj)) / (Length(dObj) * Length(nObj));
        a.tBound = c > 0 ? 1 / (Length(dObj) * c) : std::numeric_limits<double>::infinity();
    }
    rep.analyticDtBound = rep.analyticHits ? errSum / double(rep.analyticHits) : 0;

    // World-space float rounding of the twin's vertices, carried to object space.
    Bounds3f wb = shape.RenderBounds();
    double maxCoord =
        std::max(MaxComponent(Abs(Vec3d(wb.pMin))), MaxComponent(Abs(Vec3d(wb.pMax))));
    double hRound =
        2 * std::sqrt(3.0) * 0x1p-24 * maxCoord * InverseScale(shape.RenderFromObject());

    // Distance of each ray to a silhouette or boundary: level-independent, computed lazily
    // (only disagreeing rays need it), in double from the analytic description.
    std::vector<double> dSil(nr, -1);
    Bounds3d ob = shape.ObjectBounds();
    auto silhouetteDistance = [&](size_t i, double pad) {
        if (dSil[i] >= 0) return dSil[i];
        Vec3d o = objFromWorld.Point(Vec3d(rays[i].o)), d = objFromWorld.Vector(Vec3d(rays[i].d));
        Bounds3d b(ob.pMin - Vec3d(pad, pad, pad), ob.pMax + Vec3d(pad, pad, pad));
        double ta, tb;
        double dist = std::numeric_limits<double>::infinity();
        if (ClipToBounds(b, o, d, &ta, &tb))
            dist = std::min(DistanceToTangency(profile, o, d, ta, tb),
                            DistanceToBoundary(profile, o, d, ta, tb));
        dSil[i] = dist;
        return dist;
    };
    double extent = Length(ob.Diagonal());

    for (int n : options.levels) {
        LevelStats L;
        TessellatedMesh tm;
        try {
            Tessellate(shape, n, &tm);
        } catch (const std::length_error &e) {
            rep.note = e.what();
            break;  // finer levels would be larger still
        }
        L.nPhi = tm.nPhi;
        L.nV = tm.nV;
        L.triangles = tm.indices.size() / 3;
        L.h = ChordError(profile, tm) * (1 + 1e-6) + hRound;
        AccelOptions mOpt;
        mOpt.robust = true;
        Accel mesh(mOpt);
        mesh.AddMesh(MakeTessellatedMesh(shape, n));
        mesh.Commit();
        L.buildMs = mesh.BuildSeconds() * 1e3;
        const TriangleMesh &tri = *mesh.Mesh(0);

        std::vector<RawHit> rawM(nr);
        std::vector<char> hitM(nr);
        L.nsPerRayMesh = TimedPass(mesh, rays, &hitM, &rawM);

        // Silhouette distances are measured on the bounds padded by a few h so the ray
        // segment covers every triangle.
        double pad = 4 * L.h + 1e-12 * extent;
        std::vector<double> dts;
        double boundSum = 0, nErrSum = 0, sErrSum = 0;
        for (size_t i = 0; i < nr; ++i) {
            bool a = hitA[i], m = hitM[i];
            L.analyticHits += a;
            L.meshHits += m;
            if (a != m) {
                ++L.disagree;
                double ds = silhouetteDistance(i, pad);
                if (ds < L.h) {
                    ++L.inBand;
                } else {
                    ++L.outOfBand;
                    if (a) {
                        ++L.leaks;
                        if (ds > 10 * L.h) ++L.deepLeaks;
                    } else {
                        ++L.phantoms;
                    }
                }
                continue;
            }
            if (!a) continue;
            double dt = std::abs(double(rawM[i].t) - double(ar[i].t));
            double bound = L.h * ar[i].tBound + 4 * UlpF(std::max(rawM[i].t, ar[i].t));
            if (dt > 2 * bound) {
                // Curvature allows up to twice h / cos (grazing entry into a convex shape);
                // beyond that the two hits are on different sheets, which only a ray near a
                // silhouette may see.
                if (silhouetteDistance(i, pad) < L.h) {
                    ++L.sheetSwitch;
                    continue;
                }
                ++L.outOfBand;
            }
            dts.push_back(dt);
            boundSum += bound;
            if (dt > bound) ++L.dtOverBound;
            if (bound > 0 && std::isfinite(bound))
                L.dtRatioMax = std::max(L.dtRatioMax, dt / bound);
            Vec3f ng = tri.GeometricNormal(size_t(rawM[i].prim));
            double e = AngleDeg(ar[i].n, ng);
            if (e > 90) ++L.flippedNormals;
            nErrSum += e;
            L.normalErrMax = std::max(L.normalErrMax, e);
            SurfaceInteraction sm = mesh.Interaction(rays[i], rawM[i]);
            double es = AngleDeg(ar[i].n, sm.ns);
            sErrSum += es;
            L.shadingErrMax = std::max(L.shadingErrMax, es);
        }
        L.dtCount = int64_t(dts.size());
        if (!dts.empty()) {
            double sum = 0;
            for (double x : dts) sum += x;
            L.dtMean = sum / double(dts.size());
            std::sort(dts.begin(), dts.end());
            L.dtMax = dts.back();
            L.dtP99 = dts[std::min(dts.size() - 1, size_t(0.99 * double(dts.size())))];
            L.dtBoundMean = boundSum / double(dts.size());
            L.normalErrMean = nErrSum / double(dts.size());
            L.shadingErrMean = sErrSum / double(dts.size());
        }
        rep.levels.push_back(L);
    }

    // ---- Convergence of the mean shading-normal error with n (degrees; below 1e-3 at every
    // level is rounding: float normals).
    {
        std::vector<double> sx, sy;
        for (const LevelStats &l : rep.levels)
            if (l.shadingErrMean > 1e-3) {
                sx.push_back(std::log(double(l.nPhi)));
                sy.push_back(std::log(l.shadingErrMean));
            }
        rep.shadingSlopeApplicable = sx.size() >= 2;
        if (rep.shadingSlopeApplicable) {
            rep.shadingSlope = Slope(sx, sy, nullptr);
            rep.shadingSlopeOk = rep.shadingSlope <= -1.7;
        }
    }

    // ---- Convergence of mean |dt| with n.
    std::vector<double> lx, ly;
    double h0 = rep.levels.empty() ? 0 : rep.levels.front().h;
    double dtTop = 0;
    for (const LevelStats &l : rep.levels) dtTop = std::max(dtTop, l.dtMean);
    if (rep.levels.size() < 2) {
        rep.slopeApplicable = false;
        rep.note = "fewer than two levels: no slope";
    } else if (dtTop < 1e-3 * h0) {
        // The disk: its triangles lie exactly in its plane, so t agrees to rounding at every
        // level and only the rim's chord error (hit/miss near the edge) converges.
        rep.slopeApplicable = false;
        rep.note =
            "mean |dt| at rounding level at every n (tessellation exact in the surface): "
            "no slope to fit";
    } else {
        for (const LevelStats &l : rep.levels)
            if (l.dtMean > 0) {
                lx.push_back(std::log(double(l.nPhi)));
                ly.push_back(std::log(l.dtMean));
            }
        double icept = 0;
        rep.slope = Slope(lx, ly, &icept);
        rep.slopeOk = rep.slope >= -2.3 && rep.slope <= -1.7;
        // Equal accuracy: where the fitted mean |dt| meets the analytic error bound.
        if (rep.analyticDtBound > 0 && rep.slope < 0) {
            double nStar = std::exp((std::log(rep.analyticDtBound) - icept) / rep.slope);
            rep.equalAccuracyLevel = nStar;
            std::vector<double> tx, ty;
            for (const LevelStats &l : rep.levels) {
                tx.push_back(std::log(double(l.nPhi)));
                ty.push_back(l.nsPerRayMesh);
            }
            // BVH traversal cost grows with the depth, i.e. with log(triangles): fit time per
            // ray linearly in log n over all levels and evaluate it at n*.
            double ti = 0, ts = Slope(tx, ty, &ti);
            rep.equalAccuracyNsPerRay = ti + ts * std::log(nStar);
            rep.equalAccuracyExtrapolated = nStar > double(rep.levels.back().nPhi);
        }
    }
    return rep;
}

// The shapes on the list (geometry/shape_list.inc), plus a partial sphere right after the
// sphere (zone and wedge: the cut edges of a quadric).
std::vector<std::string> CanonicalShapeNames() {
    std::vector<std::string> names;
#define PRISM_SHAPE(T, name) \
    names.push_back(name);   \
    if (names.back() == "sphere") names.push_back("partial-sphere");
#include "geometry/shape_list.inc"
#undef PRISM_SHAPE
    return names;
}

std::unique_ptr<AnalyticShape> MakeCanonicalShape(const std::string &name) {
    // A fixed similarity transform off the origin and off the axes, so no symmetry of the
    // object frame hides a bug.
    Transform w =
        Translate(Vec3d(0.25, -0.5, 1.0)) * Rotate(37, Vec3d(1, 2, 3)) * Scale(1.5, 1.5, 1.5);
    if (name == "partial-sphere") return std::make_unique<Sphere>(w, false, 1, -0.5, 0.3, 270);
#define PRISM_SHAPE(T, n) \
    if (name == n) return CanonicalShape<T>(w);
#include "geometry/shape_list.inc"
#undef PRISM_SHAPE
    return nullptr;
}

std::string FormatReport(const ShapeReport &r) {
    std::string s;
    char buf[512];
    std::snprintf(buf, sizeof(buf),
                  "%s: %lld rays, analytic %lld hits, %.1f ns/ray (%.2f Mrays/s), "
                  "analytic t-error bound (mean) %.3g\n",
                  r.name.c_str(), (long long)r.rays, (long long)r.analyticHits, r.nsPerRayAnalytic,
                  r.nsPerRayAnalytic > 0 ? 1e3 / r.nsPerRayAnalytic : 0.0, r.analyticDtBound);
    s += buf;
    if (r.levels.empty()) {
        s += "  " + r.note + "\n";
        return s;
    }
    s += "     n    nV      tris          h  disagree%  inband  OUTBAND  |dt|mean    |dt|p99    "
         "|dt|max  >bound  maxratio  nErr(deg) nsErr(deg)  ns/ray  Mrays/s  build ms\n";
    for (const LevelStats &l : r.levels) {
        std::snprintf(buf, sizeof(buf),
                      "  %4d  %4d  %8zu  %9.3g  %8.4f  %6lld  %7lld  %9.3g  %9.3g  %9.3g  %6lld  "
                      "%8.3f  %9.4f  %9.4f  %6.1f  %7.2f  %8.1f\n",
                      l.nPhi, l.nV, l.triangles, l.h,
                      r.rays ? 100.0 * double(l.disagree) / double(r.rays) : 0.0,
                      (long long)l.inBand, (long long)l.outOfBand, l.dtMean, l.dtP99, l.dtMax,
                      (long long)l.dtOverBound, l.dtRatioMax, l.normalErrMean, l.shadingErrMean,
                      l.nsPerRayMesh, l.nsPerRayMesh > 0 ? 1e3 / l.nsPerRayMesh : 0.0, l.buildMs);
        s += buf;
    }
    int64_t leaks = 0, deep = 0;
    std::string per;
    for (const LevelStats &l : r.levels) {
        leaks += l.leaks;
        deep += l.deepLeaks;
        if (l.leaks) per += " n=" + std::to_string(l.nPhi) + ":" + std::to_string(l.leaks);
    }
    std::snprintf(buf, sizeof(buf), "  mesh leaks: %lld (%lld deeper than 10 h)%s\n",
                  (long long)leaks, (long long)deep, per.c_str());
    s += buf;
    for (const LevelStats &l : r.levels)
        if (l.phantoms || l.flippedNormals || l.sheetSwitch) {
            std::snprintf(buf, sizeof(buf),
                          "  n=%d: %lld phantom mesh hits, %lld sheet switches in band, %lld "
                          "flipped normals\n",
                          l.nPhi, (long long)l.phantoms, (long long)l.sheetSwitch,
                          (long long)l.flippedNormals);
            s += buf;
        }
    if (r.slopeApplicable) {
        std::snprintf(buf, sizeof(buf),
                      "  convergence slope of mean |dt|: %.3f (%s, want -2.3 to -1.7)\n", r.slope,
                      r.slopeOk ? "ok" : "FAIL");
        s += buf;
        if (r.equalAccuracyLevel > 0) {
            std::snprintf(buf, sizeof(buf),
                          "  equal accuracy (mean |dt| = analytic bound %.3g) at n = %.0f%s: "
                          "%.1f ns/ray vs analytic %.1f ns/ray\n",
                          r.analyticDtBound, r.equalAccuracyLevel,
                          r.equalAccuracyExtrapolated ? " (extrapolated)" : "",
                          r.equalAccuracyNsPerRay, r.nsPerRayAnalytic);
            s += buf;
        }
    } else {
        s += "  convergence slope: n/a: " + r.note + "\n";
    }
    if (r.shadingSlopeApplicable) {
        std::snprintf(buf, sizeof(buf),
                      "  convergence slope of mean shading-normal error: %.3f (%s, want <= -1.7)\n",
                      r.shadingSlope, r.shadingSlopeOk ? "ok" : "FAIL");
        s += buf;
    }
    if (r.OutOfBand() > 0)
        s += "  FAIL: " + std::to_string(r.OutOfBand()) +
             " disagreements outside the chord-error band\n";
    return s;
}

std::string ResultsCsv(const std::vector<ShapeReport> &reports) {
    std::string s =
        "shape,level,n_v,triangles,rays,h,analytic_hits,mesh_hits,disagree_rate,in_band,"
        "out_of_band,leaks,deep_leaks,phantoms,sheet_switch,dt_mean,dt_p99,dt_max,dt_bound,"
        "dt_over_bound,dt_ratio_max,normal_err_deg_mean,normal_err_deg_max,shading_err_deg_mean,"
        "shading_err_deg_max,ns_per_ray_analytic,ns_per_ray_mesh,mrays_analytic,mrays_mesh,"
        "build_ms,analytic_dt_bound,slope,equal_accuracy_level,equal_accuracy_ns_per_ray,"
        "shading_slope\n";
    char buf[1024];
    for (const ShapeReport &r : reports)
        for (const LevelStats &l : r.levels) {
            std::snprintf(
                buf, sizeof(buf),
                "%s,%d,%d,%zu,%lld,%.6g,%lld,%lld,%.6g,%lld,%lld,%lld,%lld,%lld,%lld,%.6g,%.6g,"
                "%.6g,%.6g,%lld,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%s,%.6g,%."
                "6g,%s\n",
                r.name.c_str(), l.nPhi, l.nV, l.triangles, (long long)r.rays, l.h,
                (long long)l.analyticHits, (long long)l.meshHits,
                r.rays ? double(l.disagree) / double(r.rays) : 0.0, (long long)l.inBand,
                (long long)l.outOfBand, (long long)l.leaks, (long long)l.deepLeaks,
                (long long)l.phantoms, (long long)l.sheetSwitch, l.dtMean, l.dtP99, l.dtMax,
                l.dtBoundMean, (long long)l.dtOverBound, l.dtRatioMax, l.normalErrMean,
                l.normalErrMax, l.shadingErrMean, l.shadingErrMax, r.nsPerRayAnalytic,
                l.nsPerRayMesh, r.nsPerRayAnalytic > 0 ? 1e3 / r.nsPerRayAnalytic : 0.0,
                l.nsPerRayMesh > 0 ? 1e3 / l.nsPerRayMesh : 0.0, l.buildMs, r.analyticDtBound,
                r.slopeApplicable ? std::to_string(r.slope).c_str() : "", r.equalAccuracyLevel,
                r.equalAccuracyNsPerRay,
                r.shadingSlopeApplicable ? std::to_string(r.shadingSlope).c_str() : "");
            s += buf;
        }
    return s;
}

int ValidationStatus(const std::vector<ShapeReport> &reports) {
    bool slopeBad = false;
    for (const ShapeReport &r : reports) {
        if (r.OutOfBand() > 0) return ExitOutOfBand;
        if (r.slopeApplicable && !r.slopeOk) slopeBad = true;
        if (r.shadingSlopeApplicable && !r.shadingSlopeOk) slopeBad = true;
    }
    return slopeBad ? ExitBadSlope : 0;
}

}  // namespace prism
