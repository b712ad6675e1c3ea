// The lens of pbrt-v3's "realistic" camera: a stack of spherical interfaces and an aperture
// stop (a lens description file's rows), rays traced through it from the film, the film
// distance that focuses it (thick-lens approximation), and the exit pupil's bounds per film
// radius for sampling only rays that can pass (pbrt-v3 RealisticCamera, PBR 3rd ed. 6.4).
//
// Camera space as the other cameras': the film at z = 0 looking along +z, the lens in front
// of it; the rear interface (the last row) at z = the film distance, each earlier one a row's
// thickness further. Radius > 0: the centre of curvature lies toward the film (the surface
// bulges toward the scene); radius 0: the aperture stop (a disk).
#pragma once

#include <vector>

#include "core/vecmath.h"
#include "geometry/ray.h"

namespace prism {

struct LensInterface {
    double radius = 0;          // of curvature, metres; 0: the aperture stop
    double thickness = 0;       // to the next interface toward the film (the last: the film)
    double eta = 1;             // index of refraction behind it (toward the film); 0 is air
    double apertureRadius = 0;  // metres
};

// A ray in camera space (double precision: lens tracing needs it).
struct LensRay {
    Vec3d o, d;
};

class LensSystem {
  public:
    // interfaces: scene side first (their thicknesses as given); filmDiagonal: metres;
    // shutterTime: the shutter's open interval (physical weighting scales by it). Throws
    // std::invalid_argument when the lens cannot focus at focusDistance (metres from the film).
    LensSystem(std::vector<LensInterface> interfaces, double focusDistance, double filmDiagonal,
               bool simpleWeighting, double shutterTime = 1);

    // Traces r (from the film, toward +z) through every interface: false when an interface
    // or the stop blocks it (or it reflects totally). *out: the ray leaving the front.
    bool TraceFromFilm(const LensRay &r, LensRay *out) const;
    // The reverse: r from the scene (toward -z) to the film side.
    bool TraceFromScene(const LensRay &r, LensRay *out) const;

    // The camera ray from camera-space film point (x, y, 0) through the exit pupil sample
    // u in [0,1)^2; *weight: pbrt-v3's (cos^4 times the pupil's area, normalized by the
    // pupil at the film's centre with simple weighting, else times the shutter time over the
    // rear distance squared);
    // 0 when the lens blocks the ray.
    LensRay GenerateRay(Vec2d pFilm, Vec2d u, double *weight) const;

    double FilmDistance() const { return interfaces_.back().thickness; }
    double RearZ() const { return interfaces_.back().thickness; }
    double FrontZ() const;
    // Paraxial focal length (rear side) and the principal planes' z, film side and scene side.
    void CardinalPoints(double *focalLength, double *pRear, double *pFront) const;
    // The exit pupil's bounds on the rear plane for film points on +x at radius r.
    struct Box {
        double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
        double Area() const { return std::max(0.0, x1 - x0) * std::max(0.0, y1 - y0); }
    };
    const Box &PupilBounds(double r) const;

  private:
    bool Trace(const LensRay &r, LensRay *out, bool fromFilm) const;
    void ComputePupils();
    std::vector<LensInterface> interfaces_;
    std::vector<double> z_;  // each interface's vertex
    double filmRadius_;      // half the film diagonal
    bool simple_;
    double shutterTime_;
    std::vector<Box> pupils_;  // per radial interval of [0, filmRadius_]
};

}  // namespace prism
