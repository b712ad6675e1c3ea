#include "core/vecmath.h"

#include <cstdio>

namespace prism {

template <typename T>
static std::string Format3(const Vec3<T> &v) {
    char buf[128];
    std::snprintf(buf, sizeof(buf), "[%.9g, %.9g, %.9g]", double(v.x), double(v.y), double(v.z));
    return buf;
}
std::string ToString(const Vec3f &v) { return Format3(v); }
std::string ToString(const Vec3d &v) { return Format3(v); }

}  // namespace prism
