#include "tools/validate/tessellate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disk.h"
#include "geometry/hyperboloid.h"
#include "geometry/paraboloid.h"
#include "geometry/quadric_util.h"
#include "geometry/sphere.h"
#include "geometry/torus.h"

namespace prism {

using Kind = RevolutionProfile::Kind;

int RingsFor(const RevolutionProfile &profile, int nPhi) {
    double turn = profile.Turning();
    if (profile.kind == Kind::Sphere) {
        // n_theta = n_phi / 2 for the full sphere, proportionally for a zone.
        return std::max(1, int(std::lround(0.5 * nPhi * turn / Pi)));
    }
    if (turn < 1e-12) return 1;  // straight profile: one ring of triangles is exact along v
    // Rounded (not ceil'd) so the ring count stays proportional to nPhi across levels.
    return std::max(1, int(std::lround(nPhi * turn / (2 * Pi))));
}

// ---------------------------------------------------------------------------------------------
// Tessellation.

namespace {

// The ring count for `nPhi` segments (raised to the minimum); throws std::length_error beyond
// MaxTessellationTriangles.
int CheckedRings(const AnalyticShape &shape, const RevolutionProfile &pr, int *nPhi) {
    *nPhi = std::max(*nPhi, pr.FullCircle() ? 3 : 1);
    int nV = RingsFor(pr, *nPhi);
    if (double(*nPhi) * nV * 2 > double(MaxTessellationTriangles))
        throw std::length_error("tessellating a " + std::string(shape.Name()) + " with " +
                                std::to_string(*nPhi) + " segments needs more than " +
                                std::to_string(MaxTessellationTriangles) + " triangles");
    return nV;
}

}  // namespace

bool TessellationSize(const AnalyticShape &shape, int nPhi, uint64_t *vertices,
                      uint64_t *triangles) {
    RevolutionProfile pr;
    if (!shape.Revolution(&pr)) return false;
    int nV = CheckedRings(shape, pr, &nPhi);
    // Rings of nPhi + 1 columns (poles have one vertex), two triangles per grid cell.
    *vertices = uint64_t(nV + 1) * uint64_t(nPhi + 1);
    *triangles = 2 * uint64_t(nPhi) * uint64_t(nV);
    return true;
}

bool Tessellate(const AnalyticShape &shape, int nPhi, TessellatedMesh *mesh) {
    RevolutionProfile pr;
    if (!shape.Revolution(&pr)) return false;
    bool full = pr.FullCircle();
    int nV = CheckedRings(shape, pr, &nPhi);
    *mesh = TessellatedMesh{};
    mesh->nPhi = nPhi;
    mesh->nV = nV;
    int nCol = full ? nPhi : nPhi + 1;
    int nRing = pr.closedV ? nV : nV + 1;
    auto isPole = [&](int j) { return (j == 0 && pr.poleV0) || (j == nV && pr.poleV1); };

    std::vector<uint32_t> ringStart(size_t(nRing) + 1);
    for (int j = 0; j < nRing; ++j) {
        ringStart[size_t(j)] = uint32_t(mesh->P.size());
        double v = double(j) / nV;
        int cols = isPole(j) ? 1 : nCol;
        for (int i = 0; i < cols; ++i) {
            double phi = i == nPhi ? pr.phiMax : pr.phiMax * i / nPhi;
            Vec3d p = pr.Surface(phi, v);
            // One projection step where the parametric form is not exact to rounding.
            if (pr.kind == Kind::Sphere) p *= pr.a / Length(p);
            ObjectHit oh;
            oh.p = p;
            oh.phi = phi;
            LocalGeometry g = shape.Geometry(oh);
            Vec3d n = g.n;
            // A fan's apex: at a sphere's or paraboloid's pole and the disk's centre the normal
            // is the axis. The cone's apex has none (each generator has its own): N holds the
            // axis there, and apexVertex marks it for MakeTessellatedMesh.
            if (isPole(j)) n = Vec3d(0, 0, n.z >= 0 ? 1 : -1);
            if (isPole(j) && pr.kind == Kind::Cone) mesh->apexVertex = int(mesh->P.size());
            double len = Length(n);
            mesh->P.push_back(p);
            mesh->N.push_back(len > 0 ? n / len : Vec3d(0, 0, 1));
            mesh->uv.push_back(g.uv);
        }
    }
    auto vert = [&](int i, int j) -> uint32_t {
        if (pr.closedV && j == nV) j = 0;
        if (isPole(j)) return ringStart[size_t(j)];
        if (full && i == nPhi) i = 0;
        return ringStart[size_t(j)] + uint32_t(i);
    };
    // Column by column so that column 0's triangles come first (ChordError uses them).
    for (int i = 0; i < nPhi; ++i) {
        for (int j = 0; j < nV; ++j) {
            uint32_t a = vert(i, j), b = vert(i + 1, j), c = vert(i, j + 1), d = vert(i + 1, j + 1);
            if (a != b) mesh->indices.insert(mesh->indices.end(), {a, b, d});
            if (c != d) mesh->indices.insert(mesh->indices.end(), {a, d, c});
        }
    }
    // Winding: (p1 - p0) x (p2 - p0) must agree with the analytic normal. The grid order above
    // gives dP/dphi x dP/dv; whether that is the shape's orientation depends on the shape
    // (the hyperboloid's on the order of p1 and p2), so vote and flip once.
    double vote = 0;
    for (size_t t = 0; t < mesh->indices.size(); t += 3) {
        const uint32_t *v = &mesh->indices[t];
        Vec3d cr = Cross(mesh->P[v[1]] - mesh->P[v[0]], mesh->P[v[2]] - mesh->P[v[0]]);
        vote += Dot(cr, mesh->N[v[0]] + mesh->N[v[1]] + mesh->N[v[2]]) > 0 ? 1 : -1;
    }
    if (vote < 0)
        for (size_t t = 0; t < mesh->indices.size(); t += 3)
            std::swap(mesh->indices[t + 1], mesh->indices[t + 2]);
    return true;
}

std::unique_ptr<TriangleMesh> MakeTessellatedMesh(const AnalyticShape &shape, int nPhi,
                                                  const MeshCharge &charge) {
    uint64_t nv = 0, nt = 0;
    if (charge && TessellationSize(shape, nPhi, &nv, &nt))
        // The mesh, and the double-precision tessellation and float copies it is made from.
        charge(TriangleMesh::Bytes(nv, 3 * nt, true, true),
               nv * (sizeof(Vec3d) * 2 + sizeof(Vec2d) + sizeof(Vec3f) * 2 + sizeof(Vec2f)) +
                   3 * nt * sizeof(uint32_t));
    TessellatedMesh m;
    if (!Tessellate(shape, nPhi, &m)) return nullptr;
    const Transform &w = shape.RenderFromObject();
    // TriangleMesh flips (p1-p0)x(p2-p0) by ReverseOrientation XOR handedness, while the
    // analytic normal is the transformed gradient flipped by the same flag. A mirroring
    // transform also mirrors the cross product, so the twin reverses its winding there to
    // keep the two normals equal.
    if (w.SwapsHandedness())
        for (size_t t = 0; t < m.indices.size(); t += 3)
            std::swap(m.indices[t + 1], m.indices[t + 2]);
    std::vector<Vec3f> P(m.P.size()), N(m.N.size());
    std::vector<Vec2f> uv(m.uv.size());
    // The analytic normal is flipped by FlipNormals() = ReverseOrientation XOR handedness;
    // TriangleMesh flips shading normals by ReverseOrientation alone, so the twin's are
    // flipped here by the rest: the handedness.
    double s = w.SwapsHandedness() ? -1 : 1;
    for (size_t i = 0; i < m.P.size(); ++i) {
        P[i] = Vec3f(m.P[i]);
        N[i] = Vec3f(m.N[i] * s);
        uv[i] = Vec2f(float(m.uv[i].x), float(m.uv[i].y));
    }
    // The cone's apex gets a zero shading normal: the fan's interpolation is then the blend of
    // the two rim normals, which points along the generator through the hit (O(n^-2) off, like
    // the rest of the surface; the axis was 56 degrees off at every n for r = 1, h = 1.5).
    if (m.apexVertex >= 0) N[size_t(m.apexVertex)] = Vec3f(0, 0, 0);
    // TriangleMesh rounds the object-space float vertices after transforming in double; pass
    // it the float vertices (the rounding is part of the measured chord-error band).
    return std::make_unique<TriangleMesh>(w, shape.FlipNormals() != w.SwapsHandedness(), P,
                                          std::move(m.indices), N, std::move(uv));
}

std::function<std::unique_ptr<TriangleMesh>(const AnalyticShape &, const MeshCharge &)>
TessellateWith(int nPhi) {
    return [nPhi](const AnalyticShape &shape, const MeshCharge &charge) {
        return MakeTessellatedMesh(shape, nPhi, charge);
    };
}

// ---------------------------------------------------------------------------------------------
// Distances.

namespace {

// Golden-section minimization of f over [lo, hi].
template <typename F>
double GoldenMin(F &&f, double lo, double hi, double *xMin, int iters = 70) {
    const double g = 0.6180339887498949;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = f(x1), f2 = f(x2);
    for (int k = 0; k < iters && hi - lo > 0; ++k) {
        if (f1 < f2) {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = f(x2);
        }
    }
    double best = f1 < f2 ? f1 : f2;
    *xMin = f1 < f2 ? x1 : x2;
    double fl = f(lo), fh = f(hi);  // the ends, for monotonic functions
    if (fl < best) {
        best = fl;
        *xMin = lo;
    }
    if (fh < best) {
        best = fh;
        *xMin = hi;
    }
    return best;
}

// Minimum of f over [0, 1]: a scan of K + 1 samples, then golden section on the bracket
// around the best one (f may have several local minima; the scan picks the basin).
template <typename F>
double ScanThenGoldenMin(F &&f, int K, double *xMin) {
    int best = 0;
    double bestF = f(0.0);
    for (int k = 1; k <= K; ++k) {
        double fk = f(double(k) / K);
        if (fk < bestF) {
            bestF = fk;
            best = k;
        }
    }
    double lo = std::max(0, best - 1) / double(K), hi = std::min(K, best + 1) / double(K);
    return GoldenMin(f, lo, hi, xMin, 80);
}

double Sign(const RevolutionProfile &pr, Vec2d q, Vec2d c, double v) {
    Vec2d t = pr.Tangent(Clamp(v, 0.0, 1.0));
    Vec2d n(t.y, -t.x);
    Vec2d e = q - c;
    return e.x * n.x + e.y * n.y >= 0 ? 1 : -1;
}

double Len2(Vec2d a) { return std::sqrt(a.x * a.x + a.y * a.y); }

// Closest point on a segment of the profile between P(0) and P(1) (straight profiles).
double SegmentDistance(const RevolutionProfile &pr, Vec2d q, double *v) {
    Vec2d p0 = pr.Point(0), p1 = pr.Point(1), e = p1 - p0;
    double l2 = e.x * e.x + e.y * e.y;
    double s = Clamp(((q.x - p0.x) * e.x + (q.y - p0.y) * e.y) / l2, 0.0, 1.0);
    Vec2d c = p0 + e * s;
    *v = s;
    return Len2(q - c) * Sign(pr, q, c, s);
}

}  // namespace

double ProfileDistance(const RevolutionProfile &pr, Vec2d q, double *vClosest) {
    double v = 0, dist = 0;
    switch (pr.kind) {
        case Kind::Sphere: {
            // Arc of the circle |q| = a between polar angles c (top) and b (bottom).
            double th = std::atan2(q.x, q.y);  // polar angle from +z, in [0, pi] for rho >= 0
            double thc = Clamp(th, std::min(pr.b, pr.c), std::max(pr.b, pr.c));
            v = (thc - pr.b) / (pr.c - pr.b);
            if (thc == th) {
                dist = Len2(q) - pr.a;
            } else {
                Vec2d c(pr.a * std::sin(thc), pr.a * std::cos(thc));
                dist = Len2(q - c) * Sign(pr, q, c, v);
            }
            break;
        }
        case Kind::Torus: {
            Vec2d e(q.x - pr.a, q.y);
            dist = Len2(e) - pr.b;
            double th = std::atan2(e.y, e.x);
            if (th < 0) th += 2 * Pi;
            v = th / (2 * Pi);
            break;
        }
        case Kind::Cylinder:
        case Kind::Disk:
        case Kind::Cone:
            dist = SegmentDistance(pr, q, &v);
            break;
        case Kind::Paraboloid:
        case Kind::Hyperboloid: {
            // Coarse scan, then golden section on the bracket around the best sample.
            auto d2 = [&](double s) {
                Vec2d e = q - pr.Point(s);
                return e.x * e.x + e.y * e.y;
            };
            double d2min = ScanThenGoldenMin(d2, 48, &v);
            dist = std::sqrt(d2min) * Sign(pr, q, pr.Point(v), v);
            break;
        }
    }
    if (vClosest) *vClosest = v;
    return dist;
}

namespace {

// Azimuth of p relative to the profile's phi = 0 at parameter v, in [0, 2pi).
double RelativePhi(const RevolutionProfile &pr, const Vec3d &p, double v) {
    double phi = std::atan2(p.y, p.x) - pr.Alpha(v);
    phi = std::fmod(phi, 2 * Pi);
    if (phi < 0) phi += 2 * Pi;
    return phi;
}

// Distance from point p to the 3-D curve B(w), w in [0, 1].
template <typename Curve>
double CurvePointDistance(Curve &&B, const Vec3d &p) {
    double w;
    return std::sqrt(ScanThenGoldenMin([&](double x) { return LengthSquared(B(x) - p); }, 64, &w));
}

}  // namespace

double SurfaceDistance(const RevolutionProfile &pr, const Vec3d &p) {
    double rho = std::hypot(p.x, p.y);
    double v;
    double d = std::abs(ProfileDistance(pr, Vec2d(rho, p.z), &v));
    if (pr.FullCircle() || rho == 0) return d;
    double phi = RelativePhi(pr, p, Clamp(v, 0.0, 1.0));
    if (phi <= pr.phiMax) return d;
    // Outside the swept wedge: the nearest point is on one of the two cut edges.
    double e0 = CurvePointDistance([&](double w) { return pr.Surface(0, w); }, p);
    double e1 = CurvePointDistance([&](double w) { return pr.Surface(pr.phiMax, w); }, p);
    return std::max(d, std::min(e0, e1));
}

double ChordError(const RevolutionProfile &pr, const TessellatedMesh &mesh) {
    // Column 0's triangles come first; a column has at most 2 nV triangles.
    size_t nTri = std::min(mesh.indices.size() / 3, size_t(2 * mesh.nV));
    const int G = 8;
    double hMax = 0;
    for (size_t t = 0; t < nTri; ++t) {
        const uint32_t *v = &mesh.indices[3 * t];
        const Vec3d &p0 = mesh.P[v[0]], &p1 = mesh.P[v[1]], &p2 = mesh.P[v[2]];
        for (int i = 0; i <= G; ++i)
            for (int j = 0; i + j <= G; ++j) {
                double b1 = double(i) / G, b2 = double(j) / G;
                Vec3d q = p0 * (1 - b1 - b2) + p1 * b1 + p2 * b2;
                hMax = std::max(hMax, SurfaceDistance(pr, q));
            }
    }
    // The other direction of the Hausdorff distance matters at the rims: their chords lie
    // inside the patch (the disk's triangles are exact in the plane, only its rim is not).
    if (!pr.closedV) {
        double half = 0.5 * pr.phiMax / mesh.nPhi;
        for (double v : {0.0, 1.0}) hMax = std::max(hMax, pr.Point(v).x * (1 - std::cos(half)));
    }
    return hMax;
}

double DistanceToBoundary(const RevolutionProfile &pr, const Vec3d &o, const Vec3d &d, double t0,
                          double t1) {
    double dd = Dot(d, d);
    auto rayDist2 = [&](const Vec3d &b) {
        double t = Clamp(Dot(b - o, d) / dd, t0, t1);
        return LengthSquared(o + d * t - b);
    };
    double best = std::numeric_limits<double>::infinity();
    auto curve = [&](auto &&B) {
        const int K = 128;
        int bk = 0;
        double bd = rayDist2(B(0.0));
        for (int k = 1; k <= K; ++k) {
            double dk = rayDist2(B(double(k) / K));
            if (dk < bd) {
                bd = dk;
                bk = k;
            }
        }
        double w;
        double lo = std::max(0, bk - 1) / double(K), hi = std::min(K, bk + 1) / double(K);
        double m = GoldenMin([&](double s) { return rayDist2(B(s)); }, lo, hi, &w, 80);
        best = std::min(best, std::sqrt(m));
    };
    if (!pr.closedV) {
        if (!pr.poleV0) curve([&](double w) { return pr.Surface(w * pr.phiMax, 0.0); });
        if (!pr.poleV1) curve([&](double w) { return pr.Surface(w * pr.phiMax, 1.0); });
    }
    if (!pr.FullCircle()) {
        curve([&](double w) { return pr.Surface(0, w); });
        curve([&](double w) { return pr.Surface(pr.phiMax, w); });
    }
    return best;
}

double DistanceToTangency(const RevolutionProfile &pr, const Vec3d &o, const Vec3d &d, double t0,
                          double t1) {
    if (!(t1 > t0)) return std::numeric_limits<double>::infinity();
    struct Sample {
        double f, v;
    };
    auto eval = [&](double t) {
        Vec3d p = o + d * t;
        Sample s;
        s.f = ProfileDistance(pr, Vec2d(std::hypot(p.x, p.y), p.z), &s.v);
        return s;
    };
    // Extrema whose closest point is past a rim belong to the boundary term; extrema outside
    // the phi wedge cannot touch the patch.
    auto relevant = [&](double t, double v) {
        if (!pr.closedV && ((v <= 0 && !pr.poleV0) || (v >= 1 && !pr.poleV1))) return false;
        if (pr.FullCircle()) return true;
        Vec3d p = o + d * t;
        if (std::hypot(p.x, p.y) == 0) return true;
        return RelativePhi(pr, p, Clamp(v, 0.0, 1.0)) <= pr.phiMax;
    };
    const int M = 192;
    std::vector<Sample> s(M + 1);
    std::vector<double> ts(M + 1);
    for (int i = 0; i <= M; ++i) {
        ts[size_t(i)] = t0 + (t1 - t0) * i / M;
        s[size_t(i)] = eval(ts[size_t(i)]);
    }
    double best = std::numeric_limits<double>::infinity();
    for (int i = 1; i < M; ++i) {
        double fm = s[size_t(i - 1)].f, f = s[size_t(i)].f, fp = s[size_t(i + 1)].f;
        bool isMin = f <= fm && f <= fp, isMax = f >= fm && f >= fp;
        if (!isMin && !isMax) continue;
        double sgn = isMin ? 1 : -1;
        double tx;
        double fx = sgn * GoldenMin([&](double t) { return sgn * eval(t).f; }, ts[size_t(i - 1)],
                                    ts[size_t(i + 1)], &tx, 60);
        Sample sx = eval(tx);
        if (!relevant(tx, sx.v)) continue;
        best = std::min(best, std::abs(fx));
    }
    return best;
}

}  // namespace prism
