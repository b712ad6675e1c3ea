// Image construction (the accessors are inline in image.h).
#include "image/image.h"

namespace prism {

Image::Image(int w, int h, int c) : width(w), height(h), channels(c) {
    PRISM_CHECK(w >= 0 && h >= 0 && c >= 1);
    pixels.assign(size_t(w) * size_t(h) * size_t(c), 0.f);
}

Image Image::Uninitialized(int w, int h, int c) {
    PRISM_CHECK(w >= 0 && h >= 0 && c >= 1);
    Image img;
    img.width = w;
    img.height = h;
    img.channels = c;
    img.pixels.resize(size_t(w) * size_t(h) * size_t(c));
    return img;
}

}  // namespace prism
