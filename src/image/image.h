// In-memory float image: row-major, interleaved channels, y = 0 is the top row.
// Pixel values are linear; encoding to and from files lives in image_io.h.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/check.h"
#include "core/color.h"

namespace prism {

// std::allocator, except that value-initialization (vector(n), resize(n)) leaves the elements
// uninitialized: an image whose every pixel is about to be written is allocated without
// touching its pages (the render's film writes its tiles from the worker threads, so a frame's
// page faults are taken in parallel, not up front on one thread).
template <class T>
struct NoInitAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = NoInitAllocator<U>;
    };
    NoInitAllocator() = default;
    template <class U>
    NoInitAllocator(const NoInitAllocator<U> &) noexcept {}
    template <class U>
    void construct(U *p) noexcept {
        ::new (static_cast<void *>(p)) U;
    }
    template <class U, class... Args>
    void construct(U *p, Args &&...args) {
        ::new (static_cast<void *>(p)) U(std::forward<Args>(args)...);
    }
};
using PixelVector = std::vector<float, NoInitAllocator<float>>;

struct Image {
    int width = 0, height = 0, channels = 3;
    // resize(n) leaves new values uninitialized (NoInitAllocator); assign(n, v) fills.
    PixelVector pixels;
    // The CIE xy chromaticities of its RGB primaries and white (red x y, green, blue, white),
    // when they are not sRGB's: an EXR output records them in its header.
    std::optional<std::array<float, 8>> chromaticities;

    Image() = default;
    // Zero-filled image; channels is 1, 3 or 4 (gray, RGB, RGBA) by convention.
    Image(int w, int h, int c = 3);
    // The same size with uninitialized pixels, for a writer that sets every one of them.
    static Image Uninitialized(int w, int h, int c = 3);

    size_t PixelOffset(int x, int y) const {
        PRISM_DCHECK(x >= 0 && x < width && y >= 0 && y < height);
        return (size_t(y) * size_t(width) + size_t(x)) * size_t(channels);
    }
    float &At(int x, int y, int c) {
        PRISM_DCHECK(c >= 0 && c < channels);
        return pixels[PixelOffset(x, y) + size_t(c)];
    }
    float At(int x, int y, int c) const {
        PRISM_DCHECK(c >= 0 && c < channels);
        return pixels[PixelOffset(x, y) + size_t(c)];
    }

    // Gray (1 or 2 channels) is replicated to RGB; alpha is ignored.
    RGB GetRGB(int x, int y) const {
        const float *p = &pixels[PixelOffset(x, y)];
        return channels >= 3 ? RGB(p[0], p[1], p[2]) : RGB(p[0]);
    }
    // A gray image stores the average of the components; alpha is left unchanged.
    void SetRGB(int x, int y, const RGB &c) {
        float *p = &pixels[PixelOffset(x, y)];
        if (channels >= 3) {
            p[0] = c.r;
            p[1] = c.g;
            p[2] = c.b;
        } else {
            p[0] = c.Average();
        }
    }

    bool Empty() const { return width <= 0 || height <= 0; }
    bool HasAlpha() const { return channels == 2 || channels == 4; }
};

}  // namespace prism
