// `prism validate`: cross-checks each analytic intersector against Embree's triangles on its
// tessellated twin (docs/SHAPES.md V1), with every disagreement explained by the chord-error
// band or reported. The library half, so tests can run it on test-only (broken) shapes.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geometry/ray.h"
#include "geometry/shape.h"

namespace prism {

struct ValidateOptions {
    std::vector<int> levels{8, 16, 32, 64, 128, 256, 512, 1024};  // n_phi of the twins
    int rays = 100000;  // random rays per shape (camera rays come on top)
    uint64_t seed = 1;
    Precision precision = Precision::Double;  // of the analytic intersector
};

// One tessellation level of one shape. Distances are in the shape's object space; t and
// times are per ray of the whole set.
struct LevelStats {
    int nPhi = 0, nV = 0;
    size_t triangles = 0;
    double h = 0;  // chord-error band: max triangle-to-surface distance + rounding
    int64_t analyticHits = 0, meshHits = 0;
    int64_t disagree = 0;     // hit/miss differs
    int64_t inBand = 0;       // ...with the ray within h of a silhouette or boundary
    int64_t outOfBand = 0;    // hit/miss or t disagreements no chord error explains
    int64_t leaks = 0;        // analytic hit farther than h inside the silhouette, mesh miss
    int64_t deepLeaks = 0;    // ...farther than 10 h
    int64_t phantoms = 0;     // mesh hit, analytic miss, farther than h from any silhouette
    int64_t sheetSwitch = 0;  // both hit, different sheets, ray within h of a silhouette
    int64_t dtCount = 0;      // both-hit rays in the |dt| statistics
    double dtMean = 0, dtP99 = 0, dtMax = 0;
    double dtBoundMean = 0;   // mean per-ray bound h / (|d| |cos theta|) + 4 ulp(t)
    int64_t dtOverBound = 0;  // rays with |dt| above that bound (curvature allows up to 2x)
    double dtRatioMax = 0;    // max |dt| / bound
    double normalErrMean = 0, normalErrMax = 0;    // geometric normal, degrees
    double shadingErrMean = 0, shadingErrMax = 0;  // interpolated vertex normal, degrees
    int64_t flippedNormals = 0;  // geometric normal more than 90 degrees off (winding bug)
    double nsPerRayMesh = 0, buildMs = 0;
};

struct ShapeReport {
    std::string name;
    int64_t rays = 0;
    double nsPerRayAnalytic = 0;
    int64_t analyticHits = 0;
    double analyticDtBound = 0;  // mean t error bound of the analytic hits (from pError)
    std::vector<LevelStats> levels;
    // Least-squares slope of log(mean |dt|) against log(n_phi).
    double slope = 0;
    bool slopeApplicable = true;  // false when |dt| sits at rounding level (the disk)
    bool slopeOk = true;
    std::string note;
    // Least-squares slope of log(mean shading-normal error) against log(n_phi): interpolated
    // vertex normals converge as O(n^-2) too. Not applicable when the error sits at rounding
    // level at every level (the disk's normal is constant).
    double shadingSlope = 0;
    bool shadingSlopeApplicable = false;
    bool shadingSlopeOk = true;
    // Level (possibly extrapolated) where mean |dt| falls below analyticDtBound, and the
    // time per ray there.
    double equalAccuracyLevel = 0, equalAccuracyNsPerRay = 0;
    bool equalAccuracyExtrapolated = false;

    int64_t OutOfBand() const;
    int64_t Leaks() const;
};

// Seeded random rays aimed at uniform points of the shape's world bounds, from uniform
// directions, starting outside the bounds.
std::vector<Ray> RandomRaysAt(const AnalyticShape &shape, int count, uint64_t seed);

// Runs the cross-check on one shape (owned: it goes into its own Accel). extraRays (e.g. a
// scene's camera rays, in the same space as the shape) are shot as well.
ShapeReport ValidateShape(const std::string &name, std::unique_ptr<AnalyticShape> shape,
                          const std::vector<Ray> &extraRays, const ValidateOptions &options);

// The canonical instances of `prism validate --shape`, each under a fixed similarity
// transform: every shape on geometry/shape_list.inc (CanonicalShape<T>) and partial-sphere.
std::vector<std::string> CanonicalShapeNames();
std::unique_ptr<AnalyticShape> MakeCanonicalShape(const std::string &name);  // nullptr if unknown

// Text for the terminal, CSV for results.csv.
std::string FormatReport(const ShapeReport &report);
std::string ResultsCsv(const std::vector<ShapeReport> &reports);

// Exit statuses of `prism validate`: 0 all good, 3 an out-of-band disagreement (one of the two
// intersectors has a bug), 4 only a convergence slope outside [-2.3, -1.7]: of mean |dt|, or
// of the mean shading-normal error (which must fall at least as fast as n^-1.7).
inline constexpr int ExitOutOfBand = 3;
inline constexpr int ExitBadSlope = 4;
int ValidationStatus(const std::vector<ShapeReport> &reports);

}  // namespace prism
