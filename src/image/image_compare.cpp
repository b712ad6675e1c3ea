// Image comparison helpers.
#include "image/image_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace prism {

namespace {

void CheckSameSize(const Image &a, const Image &b) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument("image sizes differ: " + std::to_string(a.width) + "x" +
                                    std::to_string(a.height) + " vs " + std::to_string(b.width) +
                                    "x" + std::to_string(b.height));
}

double ComponentDiff(float a, float b) {
    if (a == b) return 0;  // also equal infinities
    if (std::isnan(a) && std::isnan(b)) return 0;
    double d = std::abs(double(a) - double(b));
    return std::isfinite(d) ? d : std::numeric_limits<double>::infinity();
}

}  // namespace

ImageDiff CompareImages(const Image &a, const Image &b, float badThreshold) {
    CheckSameSize(a, b);
    ImageDiff diff;
    double sumSq = 0, sumAbs = 0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) {
            RGB ca = a.GetRGB(x, y), cb = b.GetRGB(x, y);
            double pixelMax = 0;
            for (int c = 0; c < 3; ++c) {
                double d = ComponentDiff(ca[c], cb[c]);
                sumSq += d * d;
                sumAbs += d;
                pixelMax = std::max(pixelMax, d);
            }
            diff.maxAbs = std::max(diff.maxAbs, pixelMax);
            if (pixelMax > badThreshold) ++diff.badPixels;
        }
    }
    double n = 3.0 * double(a.width) * double(a.height);
    if (n > 0) {
        diff.rmse = std::sqrt(sumSq / n);
        diff.meanAbs = sumAbs / n;
    }
    return diff;
}

Image BoxDownsample(const Image &img, int factor) {
    if (factor < 1) throw std::invalid_argument("downsampling factor must be at least 1");
    int w = (img.width + factor - 1) / factor, h = (img.height + factor - 1) / factor;
    Image out(w, h, img.channels);
    for (int y = 0; y < h; ++y) {
        int y0 = y * factor, y1 = std::min(y0 + factor, img.height);
        for (int x = 0; x < w; ++x) {
            int x0 = x * factor, x1 = std::min(x0 + factor, img.width);
            double inv = 1.0 / (double(y1 - y0) * double(x1 - x0));
            for (int c = 0; c < img.channels; ++c) {
                double sum = 0;
                for (int yy = y0; yy < y1; ++yy)
                    for (int xx = x0; xx < x1; ++xx) sum += img.At(xx, yy, c);
                out.At(x, y, c) = float(sum * inv);
            }
        }
    }
    return out;
}

Image DiffHeatmap(const Image &a, const Image &b, float scale) {
    CheckSameSize(a, b);
    std::vector<float> err(size_t(a.width) * size_t(a.height));
    float maxErr = 0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) {
            RGB ca = a.GetRGB(x, y), cb = b.GetRGB(x, y);
            double e = 0;
            for (int c = 0; c < 3; ++c) e += ComponentDiff(ca[c], cb[c]);
            float ef = float(e / 3);
            err[size_t(y) * size_t(a.width) + size_t(x)] = ef;
            if (std::isfinite(ef)) maxErr = std::max(maxErr, ef);
        }
    }
    float s = scale > 0 ? scale : maxErr;
    Image out(a.width, a.height, 3);
    for (size_t i = 0; i < err.size(); ++i) {
        float t = s > 0 ? std::min(err[i] / s, 1.f) : (err[i] > 0 ? 1.f : 0.f);
        out.pixels[3 * i + 0] = std::clamp(3 * t, 0.f, 1.f);
        out.pixels[3 * i + 1] = std::clamp(3 * t - 1, 0.f, 1.f);
        out.pixels[3 * i + 2] = std::clamp(3 * t - 2, 0.f, 1.f);
    }
    return out;
}

}  // namespace prism
