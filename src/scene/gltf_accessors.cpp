// glTF accessors: the bounds-checked view of an accessor's elements (tinygltf validates none)
// and the readers of positions, normals, texture coordinates and indices built on it.
#include <cstring>

#include "scene/gltf_converter.h"

namespace prism::gltf_internal {

namespace {

int ComponentSize(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        case TINYGLTF_COMPONENT_TYPE_DOUBLE:
            return 8;
        default:
            return 0;
    }
}

int ComponentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        case TINYGLTF_TYPE_VEC4:
            return 4;
        case TINYGLTF_TYPE_MAT2:
            return 4;
        case TINYGLTF_TYPE_MAT3:
            return 9;
        case TINYGLTF_TYPE_MAT4:
            return 16;
        default:
            return 0;
    }
}

}  // namespace

AccessorView GltfConverter::View(int index, const std::string &what) {
    if (index < 0 || size_t(index) >= model_.accessors.size())
        Fail(what + " refers to accessor " + std::to_string(index) + ", which does not exist");
    const Where where(*this, "/accessors/" + std::to_string(index));
    const tinygltf::Accessor &a = model_.accessors[size_t(index)];
    std::string name = "accessor " + std::to_string(index) + " (" + what + ")";
    if (a.sparse.isSparse) Fail(name + " is sparse, which is not supported");
    AccessorView v;
    v.componentType = a.componentType;
    v.components = ComponentCount(a.type);
    v.normalized = a.normalized;
    v.count = a.count;
    int cs = ComponentSize(a.componentType);
    if (cs == 0 || v.components == 0) Fail(name + " has an invalid type");
    if (a.count == 0) return v;
    if (a.bufferView < 0 || size_t(a.bufferView) >= model_.bufferViews.size())
        Fail(name + " has no valid buffer view");
    const tinygltf::BufferView &bv = model_.bufferViews[size_t(a.bufferView)];
    if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
        Fail(name + ": buffer view " + std::to_string(a.bufferView) + " has no valid buffer");
    const tinygltf::Buffer &buf = model_.buffers[size_t(bv.buffer)];
    uint64_t elemSize = uint64_t(cs) * uint64_t(v.components);
    uint64_t stride = bv.byteStride ? bv.byteStride : elemSize;
    if (stride < elemSize)
        Fail(name + ": byteStride " + std::to_string(stride) +
             " is smaller than the element size " + std::to_string(elemSize));
    // All in 64-bit with the count bounded first, so nothing can overflow.
    uint64_t viewEnd = uint64_t(bv.byteOffset) + uint64_t(bv.byteLength);
    if (bv.byteOffset > buf.data.size() || viewEnd > buf.data.size())
        Fail(name + ": buffer view " + std::to_string(a.bufferView) + " reaches past the end of " +
             "its buffer (" + std::to_string(viewEnd) + " > " + std::to_string(buf.data.size()) +
             " bytes)");
    if (a.count > bv.byteLength || a.byteOffset > bv.byteLength)
        Fail(name + " reaches past the end of its buffer view");
    uint64_t need = uint64_t(a.byteOffset) + stride * (uint64_t(a.count) - 1) + elemSize;
    if (need > bv.byteLength)
        Fail(name + " reaches past the end of its buffer view (" + std::to_string(need) + " > " +
             std::to_string(bv.byteLength) + " bytes)");
    v.data = buf.data.data() + bv.byteOffset + a.byteOffset;
    v.stride = size_t(stride);
    return v;
}

// One component as double; normalized integers map to [0, 1] / [-1, 1] (glTF 2.0 §3.11).
double Component(const AccessorView &v, size_t i, int c) {
    const unsigned char *p = v.data + i * v.stride;
    switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float x;
            std::memcpy(&x, p + 4 * c, 4);
            return x;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            double x = p[c];
            return v.normalized ? x / 255.0 : x;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            int8_t x;
            std::memcpy(&x, p + c, 1);
            return v.normalized ? std::max(x / 127.0, -1.0) : x;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t x;
            std::memcpy(&x, p + 2 * c, 2);
            return v.normalized ? x / 65535.0 : x;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t x;
            std::memcpy(&x, p + 2 * c, 2);
            return v.normalized ? std::max(x / 32767.0, -1.0) : x;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t x;
            std::memcpy(&x, p + 4 * c, 4);
            return x;
        }
        case TINYGLTF_COMPONENT_TYPE_INT: {
            int32_t x;
            std::memcpy(&x, p + 4 * c, 4);
            return x;
        }
        case TINYGLTF_COMPONENT_TYPE_DOUBLE: {
            double x;
            std::memcpy(&x, p + 8 * c, 8);
            return x;
        }
    }
    return 0;
}

std::vector<Vec3f> GltfConverter::ReadVec3(int accessor, const std::string &what) {
    AccessorView v = View(accessor, what);
    const Where where(*this, "/accessors/" + std::to_string(accessor));
    if (v.components != 3) Fail(what + " accessor must be VEC3");
    if (v.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        Fail(what + " accessor must have float components");
    std::vector<Vec3f> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        out[i] =
            Vec3f(float(Component(v, i, 0)), float(Component(v, i, 1)), float(Component(v, i, 2)));
        if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y) || !std::isfinite(out[i].z))
            Fail(what + " accessor contains a value that is not a finite number");
    }
    return out;
}

std::vector<Vec2f> GltfConverter::ReadTexcoords(int accessor, const std::string &name) {
    AccessorView v = View(accessor, name);
    const Where where(*this, "/accessors/" + std::to_string(accessor));
    if (v.components != 2) Fail(name + " accessor must be VEC2");
    bool ok = v.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
              (v.normalized && (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
    if (!ok) Fail(name + " accessor must be float or normalized unsigned byte/short");
    std::vector<Vec2f> out(v.count);
    // glTF's texture origin is the top-left corner, pbrt's (and Prism's) the bottom-left.
    for (size_t i = 0; i < v.count; ++i)
        out[i] = Vec2f(float(Component(v, i, 0)), float(1.0 - Component(v, i, 1)));
    return out;
}

std::vector<int> GltfConverter::ReadIndices(int accessor, size_t vertexCount) {
    AccessorView v = View(accessor, "indices");
    const Where where(*this, "/accessors/" + std::to_string(accessor));
    if (v.components != 1) Fail("indices accessor must be SCALAR");
    if (v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        Fail("indices accessor must be unsigned byte, short or int");
    std::vector<int> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        double x = Component(v, i, 0);
        if (x >= double(vertexCount))
            Fail("index " + std::to_string(uint64_t(x)) + " in accessor " +
                 std::to_string(accessor) + " is out of range (" + std::to_string(vertexCount) +
                 " vertices)");
        out[i] = int(x);
    }
    return out;
}

}  // namespace prism::gltf_internal
