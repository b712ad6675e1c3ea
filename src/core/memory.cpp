#include "core/memory.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace prism {

uint64_t PhysicalMemoryBytes() {
    long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0) return 0;
    return uint64_t(pages) * uint64_t(pageSize);
}

uint64_t DefaultMemoryBudget() {
    uint64_t ram = PhysicalMemoryBytes();
    return ram ? ram / 4 * 3 : uint64_t(4) << 30;
}

bool ParseMemorySize(const std::string &s, uint64_t *bytes) {
    const char *begin = s.c_str();
    if (s.empty() || !(std::isdigit((unsigned char)s[0]) || s[0] == '.')) return false;
    char *end = nullptr;
    double v = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(v) || !(v > 0)) return false;
    std::string unit(end);
    for (char &c : unit) c = char(std::toupper((unsigned char)c));
    if (unit.size() >= 3 && unit.substr(unit.size() - 2) == "IB")
        unit.resize(unit.size() - 2);
    else if (unit.size() >= 2 && unit.back() == 'B')
        unit.pop_back();
    double scale = 1;
    if (unit == "" || unit == "B")
        scale = 1;
    else if (unit == "K")
        scale = 1024.0;
    else if (unit == "M")
        scale = 1024.0 * 1024;
    else if (unit == "G")
        scale = 1024.0 * 1024 * 1024;
    else if (unit == "T")
        scale = 1024.0 * 1024 * 1024 * 1024;
    else
        return false;
    double b = std::floor(v * scale);
    if (!(b >= 1) || b >= 9.2e18) return false;
    *bytes = uint64_t(b);
    return true;
}

std::string FormatBytes(uint64_t bytes) {
    const char *units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    if (bytes < 1024) return std::to_string(bytes) + " bytes";
    double v = double(bytes) / 1024;
    int u = 0;
    while (v >= 1024 && u < 5) {
        v /= 1024;
        ++u;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, v < 10 ? "%.1f %s" : "%.0f %s", v, units[u]);
    return buf;
}

std::string MemoryBudget::ExceededMessage(uint64_t bytes, uint64_t committed,
                                          std::string_view what) const {
    std::string msg(what);
    msg += " needs about " + FormatBytes(bytes);
    if (bytes > limit_ || committed == 0)
        return msg + ", more than the memory budget of " + FormatBytes(limit_);
    return msg + "; with " + FormatBytes(committed) +
           " already committed that exceeds the memory budget of " + FormatBytes(limit_);
}

void MemoryBudget::Check(uint64_t bytes, std::string_view what, const FileLoc &loc) const {
    uint64_t used = Used();
    if (bytes > limit_ || used > limit_ - bytes)
        throw MemoryBudgetError(loc, ExceededMessage(bytes, used, what), bytes, used, limit_);
}

void MemoryBudget::Charge(uint64_t bytes, std::string_view what, const FileLoc &loc) {
    uint64_t used = used_.load(std::memory_order_relaxed);
    while (true) {
        if (bytes > limit_ || used > limit_ - bytes)
            throw MemoryBudgetError(loc, ExceededMessage(bytes, used, what), bytes, used, limit_);
        if (used_.compare_exchange_weak(used, used + bytes, std::memory_order_relaxed)) return;
    }
}

void MemoryBudget::Release(uint64_t bytes) {
    uint64_t used = used_.load(std::memory_order_relaxed);
    while (!used_.compare_exchange_weak(used, used > bytes ? used - bytes : 0,
                                        std::memory_order_relaxed)) {
    }
}

namespace {

__extension__ typedef unsigned __int128 u128;  // GCC/Clang; exact 64x64-bit products

uint64_t Saturate(u128 v) {
    constexpr uint64_t kMax = std::numeric_limits<uint64_t>::max();
    return v > u128(kMax) ? kMax : uint64_t(v);
}

}  // namespace

uint64_t EstimateBvhBytes(uint64_t triangles, uint64_t userPrims) {
    return Saturate(u128(triangles) * kBvhBytesPerTriangle +
                    u128(userPrims) * kBvhBytesPerUserPrim + kBvhFixedBytes);
}

uint64_t EstimateFilmBytes(uint64_t width, uint64_t height, double filterRadiusX,
                           double filterRadiusY, int tileSize) {
    const u128 kFilmPixelBytes = 32, kImageBytes = 12, kEncodedBytes = 12;
    if (tileSize < 1) tileSize = 1;
    // Pixels of all tiles along one axis: the extent plus each tile's two margins.
    auto tileExtent = [&](uint64_t extent, double r) {
        if (!(r > 0)) r = 0;
        r = std::min(r, 1e9);
        u128 before = u128(std::max(0.0, std::ceil(r + 0.5) - 1));
        u128 after = u128(std::max(0.0, std::floor(r - 0.5) + 1));
        u128 tiles = (u128(extent) + u128(tileSize) - 1) / u128(tileSize);
        return u128(extent) + tiles * (before + after);
    };
    // Every factor below 2^63 keeps each product below 2^126 and the sum below 2^128.
    const u128 kLarge = u128(1) << 63;
    u128 tileX = tileExtent(width, filterRadiusX), tileY = tileExtent(height, filterRadiusY);
    if (tileX >= kLarge || tileY >= kLarge) return std::numeric_limits<uint64_t>::max();
    u128 pixels = u128(width) * u128(height), tilePixels = tileX * tileY;
    if (pixels >= kLarge || tilePixels >= kLarge) return std::numeric_limits<uint64_t>::max();
    return Saturate(pixels * (kFilmPixelBytes + kImageBytes + kEncodedBytes) +
                    tilePixels * kFilmPixelBytes);
}

}  // namespace prism
