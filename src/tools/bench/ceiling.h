// `prism bench ceiling`: how close the renderer comes to Embree's own traversal rate. The scene
// is rendered through the normal render path, then exactly the same camera rays plus one shadow
// ray per hit toward each light are traced through the same Embree scene with no shading, in
// the same tile-parallel TBB loop with the same thread count.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace prism {

// How the ceiling pass traces camera rays (shadow rays are always single rtcOccluded1 queries:
// Accel has no occlusion-only packet query).
enum class CeilingTraversal { Single, Packet16 };

struct CeilingOptions {
    std::string scene;
    int width = 0, height = 0;  // 0: the scene's Film
    int threads = 0;            // 0: all cores
    int repeats = 3;
    int spp = 0;  // 0: the scene's Sampler
    CeilingTraversal traversal = CeilingTraversal::Packet16;
};

struct CeilingRepeat {
    uint64_t ceilingRays = 0, renderRays = 0;
    double ceilingSeconds = 0, renderSeconds = 0;
    double CeilingMrays() const {
        return ceilingSeconds > 0 ? ceilingRays / ceilingSeconds * 1e-6 : 0;
    }
    double RenderMrays() const { return renderSeconds > 0 ? renderRays / renderSeconds * 1e-6 : 0; }
};

struct CeilingResult {
    std::vector<CeilingRepeat> repeats;
    double ceilingMrays = 0, renderMrays = 0;  // medians over the repeats
    double Ratio() const { return ceilingMrays > 0 ? renderMrays / ceilingMrays : 0; }
    int width = 0, height = 0, spp = 1, threads = 0;
    size_t triangles = 0;
    double hitFraction = 0;  // of the camera rays
};

// Loads and builds the scene once, then runs the render and the ceiling pass `repeats` times,
// interleaved. Progress lines (one per repeat) go to `log` when it is not null. Throws
// SceneError for bad scenes, std::runtime_error otherwise.
CeilingResult RunCeiling(const CeilingOptions &options, std::FILE *log);

// "ceiling A Mrays/s, render B Mrays/s, ratio R".
std::string CeilingSummary(const CeilingResult &r);

double Median(std::vector<double> v);

}  // namespace prism
