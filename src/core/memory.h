// The memory budget: its default, parsing of sizes such as "512M" or "8G", formatting for
// messages, and MemoryBudget, the running total that every large allocation of one render is
// charged to before it is made (scene files, meshes, the BVH estimate, textures, the film), so
// that many items each under the limit but together over it are refused before the work.
// The library names no command-line flag: the app appends its flag to MemoryBudgetError.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.h"

namespace prism {

// Physical RAM in bytes (0 if unknown).
uint64_t PhysicalMemoryBytes();
// 75% of physical RAM (4 GiB if that is unknown).
uint64_t DefaultMemoryBudget();
// `budget` itself, or DefaultMemoryBudget() when it is 0 ("not set").
inline uint64_t EffectiveMemoryBudget(uint64_t budget) {
    return budget ? budget : DefaultMemoryBudget();
}
// "1048576", "512K", "512M", "1.5G", "2T" (binary units; an optional trailing "B" or "iB").
// Returns false for anything else, including 0 and sizes beyond 2^63.
bool ParseMemorySize(const std::string &s, uint64_t *bytes);
// "512 MiB", "1.5 GiB", "100 bytes".
std::string FormatBytes(uint64_t bytes);

// Thrown when an allocation would exceed the memory budget. A SceneError (exit status 2, caught
// wherever scene errors are); the app recognises it to name its flag after the message.
class MemoryBudgetError : public SceneError {
  public:
    MemoryBudgetError(const FileLoc &loc, const std::string &msg, uint64_t requested,
                      uint64_t committed, uint64_t limit)
        : SceneError(loc, msg), requested_(requested), committed_(committed), limit_(limit) {}
    uint64_t Requested() const { return requested_; }  // bytes the refused item needs
    uint64_t Committed() const { return committed_; }  // bytes charged before it
    uint64_t Limit() const { return limit_; }

  private:
    uint64_t requested_, committed_, limit_;
};

// The running total of one render's memory, checked against a limit. Thread-safe: Charge may
// be called from parallel loaders. The total only grows unless Release is called, so items
// that live until the render ends (meshes, BVH, textures, film) are charged once and kept;
// scene files are charged too, as the description parsed from them is of comparable size.
class MemoryBudget {
  public:
    // `limit` in bytes; 0 means DefaultMemoryBudget() (75% of RAM).
    explicit MemoryBudget(uint64_t limit = 0) : limit_(EffectiveMemoryBudget(limit)) {}
    MemoryBudget(const MemoryBudget &) = delete;
    MemoryBudget &operator=(const MemoryBudget &) = delete;

    // Adds `bytes` to the total, or throws MemoryBudgetError at `loc` (the total unchanged)
    // when the total would exceed the limit. `what` names the item ("mesh", "scene file
    // \"a.pbrt\"", "texture \"wood.png\""). The message is
    //   `<what> needs about X, more than the memory budget of L`             (alone too large)
    //   `<what> needs about X; with C already committed that exceeds the memory budget of L`
    void Charge(uint64_t bytes, std::string_view what, const FileLoc &loc = {});
    // Throws exactly as Charge would, without adding: for transient buffers that are freed
    // before the next item is charged.
    void Check(uint64_t bytes, std::string_view what, const FileLoc &loc = {}) const;
    // Whether Charge(bytes) would succeed now.
    bool Fits(uint64_t bytes) const { return bytes <= Remaining(); }
    // Gives back bytes charged earlier (for memory freed before the render, e.g. a file read
    // twice). Never below zero.
    void Release(uint64_t bytes);

    uint64_t Limit() const { return limit_; }
    uint64_t Used() const { return used_.load(std::memory_order_relaxed); }
    uint64_t Remaining() const {
        uint64_t used = Used();
        return used < limit_ ? limit_ - used : 0;
    }
    // The message Charge throws for `bytes` with `committed` bytes already charged.
    std::string ExceededMessage(uint64_t bytes, uint64_t committed, std::string_view what) const;

  private:
    uint64_t limit_;
    std::atomic<uint64_t> used_{0};
};

// Estimated peak memory of building Embree 3's BVH (RTC_BUILD_QUALITY_MEDIUM, shared vertex
// and index buffers, so the mesh arrays themselves are not included) over `triangles`
// triangles and `userPrims` user-geometry primitives, each in its own RTCGeometry as Prism
// attaches analytic shapes. Charge it before rtcCommitScene. Embree reports no sizes, so the
// figures were measured as the growth of peak RSS (VmHWM, reset before the commit) around
// rtcCommitScene with Embree 3.13 on an AVX-512 machine:
//   1M triangles (one mesh): 94 bytes/triangle peak, 61 retained; 100k: 107 peak, 78 retained;
//   4M triangles: 99 peak, 67 retained;
//   100k user primitives, one geometry each: 290 bytes each, geometry objects included
//   (144 bytes/primitive of BVH at the commit peak).
// The constants round these up: 112 bytes per triangle, 320 per user primitive, plus 1 MiB.
constexpr uint64_t kBvhBytesPerTriangle = 112;
constexpr uint64_t kBvhBytesPerUserPrim = 320;
constexpr uint64_t kBvhFixedBytes = uint64_t(1) << 20;
uint64_t EstimateBvhBytes(uint64_t triangles, uint64_t userPrims);

// Estimated memory of the film for a crop window of `width` x `height` pixels, a pixel filter
// of radius (`filterRadiusX`, `filterRadiusY`) and square tiles of `tileSize` pixels, as the
// renderer keeps it (render/renderer.cpp, image/film.h):
//   - the Film: one FilmPixel (4 doubles, 32 bytes) per pixel;
//   - every tile until it is merged: 32 bytes per pixel of the tile grown by the filter's
//     margins, ceil(r + 0.5) - 1 pixels before and floor(r - 0.5) + 1 after on each axis
//     (Film::MakeTile), not clipped to the crop window (an upper bound at the image edges);
//   - the float RGB Image (12 bytes per pixel) and its encoded copy for the output file (at
//     most 12 bytes per pixel, for float EXR).
// For the default box filter (r = 0.5) and 16-pixel tiles (17 x 17 per tile) that is
// 32 + 36.125 + 12 + 12 = 92.125 bytes per pixel. Saturates at UINT64_MAX instead of
// overflowing; a negative or NaN radius counts as 0.
uint64_t EstimateFilmBytes(uint64_t width, uint64_t height, double filterRadiusX,
                           double filterRadiusY, int tileSize = 16);

}  // namespace prism
