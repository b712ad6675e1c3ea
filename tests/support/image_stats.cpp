#include "support/image_stats.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace prism::test {

double MeanChannel(const Image &img, int c) {
    double s = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) s += img.pixels[img.PixelOffset(x, y) + size_t(c)];
    return s / (double(img.width) * img.height);
}

RGB MeanRGB(const Image &img) {
    return RGB(float(MeanChannel(img, 0)), float(MeanChannel(img, 1)), float(MeanChannel(img, 2)));
}

double MeanValue(const Image &img) {
    double s = 0;
    for (float v : img.pixels) s += v;
    return s / double(img.pixels.size());
}

double RelL1(const Image &a, const Image &b) {
    double d = 0, m = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        d += std::abs(double(a.pixels[i]) - double(b.pixels[i]));
        m += std::abs(double(b.pixels[i]));
    }
    return d / m;
}

double MaxAbsDiff(const Image &a, const Image &b) {
    double m = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        m = std::max(m, std::abs(double(a.pixels[i]) - double(b.pixels[i])));
    return m;
}

Image RandomImage(int w, int h, int c, float lo, float hi, uint32_t seed) {
    Image img(w, h, c);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(lo, hi);
    for (float &v : img.pixels) v = dist(rng);
    return img;
}

}  // namespace prism::test
