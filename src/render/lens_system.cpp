#include "render/lens_system.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace prism {

namespace {

// The exit pupil's bounds are tabulated for this many radial intervals of the film, each from
// this many rear-plane samples squared.
constexpr int PupilIntervals = 64;
constexpr int PupilGrid = 192;

double AirIfZero(double eta) { return eta == 0 ? 1 : eta; }

// Snell's law for unit d across unit normal n (either side); false on total internal
// reflection.
bool RefractRay(const Vec3d &d, Vec3d n, double etaI, double etaT, Vec3d *out) {
    if (Dot(n, d) > 0) n = -n;
    const double eta = etaI / etaT, cosI = -Dot(n, d);
    const double sin2T = eta * eta * std::max(0.0, 1 - cosI * cosI);
    if (sin2T >= 1) return false;
    const double cosT = std::sqrt(1 - sin2T);
    *out = Normalize(d * eta + n * (eta * cosI - cosT));
    return true;
}

}  // namespace

LensSystem::LensSystem(std::vector<LensInterface> interfaces, double focusDistance,
                       double filmDiagonal, bool simpleWeighting, double shutterTime)
    : interfaces_(std::move(interfaces)),
      filmRadius_(filmDiagonal / 2),
      simple_(simpleWeighting),
      shutterTime_(shutterTime) {
    if (interfaces_.empty()) throw std::invalid_argument("the lens has no interfaces");
    auto place = [&] {
        z_.assign(interfaces_.size(), 0);
        double z = 0;
        for (size_t i = interfaces_.size(); i-- > 0;) {
            z += interfaces_[i].thickness;
            z_[i] = z;
        }
    };
    place();
    // Focus: move the lens (the film distance) so that the plane at focusDistance images
    // onto the film, by the thick-lens equation 1/so + 1/si = 1/f about the principal planes.
    double f, pRear, pFront;
    CardinalPoints(&f, &pRear, &pFront);
    const double a = focusDistance - pFront, b = pRear, disc = (a + b) * (a + b - 4 * f);
    const double delta = 0.5 * ((a - b) - std::sqrt(std::max(0.0, disc)));
    const double film = interfaces_.back().thickness + delta;
    if (!(f > 0) || !(disc >= 0) || !(film > 0) || !std::isfinite(film))
        throw std::invalid_argument("the lens cannot focus at " + std::to_string(focusDistance) +
                                    " m (focal length " + std::to_string(f * 1000) + " mm)");
    interfaces_.back().thickness = film;
    place();
    ComputePupils();
    if (pupils_[0].Area() == 0)
        throw std::invalid_argument("no ray through the lens reaches the film's centre");
}

double LensSystem::FrontZ() const { return z_.front(); }

bool LensSystem::Trace(const LensRay &r, LensRay *out, bool fromFilm) const {
    const int n = int(interfaces_.size());
    Vec3d o = r.o, d = Normalize(r.d);
    for (int k = 0; k < n; ++k) {
        const int i = fromFilm ? n - 1 - k : k;
        const LensInterface &e = interfaces_[size_t(i)];
        Vec3d p;
        if (e.radius == 0) {
            if (d.z == 0) return false;
            const double t = (z_[size_t(i)] - o.z) / d.z;
            if (!(t > 0)) return false;
            p = o + d * t;
        } else {
            // The sphere's root on the vertex's side of its centre (the vertex is the +z
            // extreme for radius > 0, the -z extreme otherwise).
            const Vec3d c(0, 0, z_[size_t(i)] - e.radius);
            const Vec3d oc = o - c;
            const double B = Dot(oc, d), C = Dot(oc, oc) - e.radius * e.radius;
            const double disc = B * B - C;
            if (disc < 0) return false;
            const double s = std::sqrt(disc);
            bool found = false;
            for (double t : {-B - s, -B + s}) {
                if (!(t > 1e-12)) continue;
                const Vec3d q = o + d * t;
                if ((e.radius > 0) != (q.z > c.z)) continue;
                p = q;
                found = true;
                break;
            }
            if (!found) return false;
        }
        if (p.x * p.x + p.y * p.y > e.apertureRadius * e.apertureRadius) return false;
        if (e.radius != 0) {
            const double etaFilm = AirIfZero(e.eta);
            const double etaScene = i > 0 ? AirIfZero(interfaces_[size_t(i - 1)].eta) : 1.0;
            const Vec3d nrm = Normalize(p - Vec3d(0, 0, z_[size_t(i)] - e.radius));
            if (!RefractRay(d, nrm, fromFilm ? etaFilm : etaScene, fromFilm ? etaScene : etaFilm,
                            &d))
                return false;
        }
        o = p;
    }
    *out = {o, d};
    return true;
}

bool LensSystem::TraceFromFilm(const LensRay &r, LensRay *out) const { return Trace(r, out, true); }

bool LensSystem::TraceFromScene(const LensRay &r, LensRay *out) const {
    return Trace(r, out, false);
}

void LensSystem::CardinalPoints(double *focalLength, double *pRear, double *pFront) const {
    double minAperture = Infinity;
    for (const LensInterface &e : interfaces_)
        minAperture = std::min(minAperture, e.apertureRadius);
    const double h = 1e-3 * minAperture;
    *focalLength = *pRear = *pFront = 0;
    // A ray parallel to the axis at height h from each side: where its exit ray crosses the
    // axis is the focal point, where it regains height h the principal plane.
    LensRay fromScene, fromFilm;
    if (!TraceFromScene({Vec3d(h, 0, FrontZ() + 1), Vec3d(0, 0, -1)}, &fromScene) ||
        !TraceFromFilm({Vec3d(h, 0, RearZ() - 1), Vec3d(0, 0, 1)}, &fromFilm))
        return;
    auto at = [](const LensRay &r, double x) { return r.o.z + (x - r.o.x) / r.d.x * r.d.z; };
    if (fromScene.d.x == 0 || fromFilm.d.x == 0) return;
    *pRear = at(fromScene, h);
    *focalLength = *pRear - at(fromScene, 0);
    *pFront = at(fromFilm, h);
}

void LensSystem::ComputePupils() {
    pupils_.assign(PupilIntervals, Box{});
    const double rear = interfaces_.back().apertureRadius * 1.5, zRear = RearZ();
    const double cell = 2 * rear / PupilGrid;
    tbb::parallel_for(0, PupilIntervals, [&](int k) {
        const double r0 = filmRadius_ * k / PupilIntervals;
        const double r1 = filmRadius_ * (k + 1) / PupilIntervals;
        Box b{Infinity, -Infinity, Infinity, -Infinity};
        bool any = false;
        for (int j = 0; j < PupilGrid; ++j)
            for (int i = 0; i < PupilGrid; ++i) {
                // Film points spread over the interval, rear points over the grid.
                const double fr = (j * PupilGrid + i + 0.5) / (PupilGrid * PupilGrid);
                const Vec3d pFilm(r0 + (r1 - r0) * fr, 0, 0);
                const Vec3d pRear(-rear + (i + 0.5) * cell, -rear + (j + 0.5) * cell, zRear);
                LensRay out;
                if (!TraceFromFilm({pFilm, pRear - pFilm}, &out)) continue;
                any = true;
                b.x0 = std::min(b.x0, pRear.x);
                b.x1 = std::max(b.x1, pRear.x);
                b.y0 = std::min(b.y0, pRear.y);
                b.y1 = std::max(b.y1, pRear.y);
            }
        // A grid cell's margin, so that bounds between the samples are not lost.
        if (any) pupils_[size_t(k)] = {b.x0 - cell, b.x1 + cell, b.y0 - cell, b.y1 + cell};
    });
}

const LensSystem::Box &LensSystem::PupilBounds(double r) const {
    const int k = int(Clamp(r / filmRadius_ * PupilIntervals, 0.0, PupilIntervals - 1.0));
    return pupils_[size_t(k)];
}

LensRay LensSystem::GenerateRay(Vec2d pFilm, Vec2d u, double *weight) const {
    const Vec3d o(pFilm.x, pFilm.y, 0);
    const double r = std::hypot(pFilm.x, pFilm.y);
    const Box &b = PupilBounds(r);
    *weight = 0;
    // The pupil sample, rotated from +x to the film point's direction.
    const double px = b.x0 + (b.x1 - b.x0) * u.x, py = b.y0 + (b.y1 - b.y0) * u.y;
    const double c = r > 0 ? pFilm.x / r : 1, s = r > 0 ? pFilm.y / r : 0;
    const Vec3d pRear(c * px - s * py, s * px + c * py, RearZ());
    const LensRay film{o, Normalize(pRear - o)};
    LensRay out;
    if (b.Area() == 0 || !TraceFromFilm(film, &out)) return film;
    const double cos2 = film.d.z * film.d.z;
    const double area = b.Area();
    *weight = simple_ ? cos2 * cos2 * area / pupils_[0].Area()
                      : shutterTime_ * cos2 * cos2 * area / (RearZ() * RearZ());
    return out;
}

}  // namespace prism
