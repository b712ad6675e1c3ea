// glTF accessors: the bounds-checked view of an accessor's elements (tinygltf validates none)
// and the readers of positions, normals, texture coordinates and indices built on it.
#include <algorithm>
#include <cstring>
#include <memory>
#include <tuple>

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

const unsigned char *GltfConverter::ViewBytes(int bufferView, uint64_t byteOffset, uint64_t bytes,
                                              const std::string &name, const std::string &role) {
    if (bufferView < 0 || size_t(bufferView) >= model_.bufferViews.size())
        Fail(name + ": " + role + " has no valid buffer view");
    const tinygltf::BufferView &bv = model_.bufferViews[size_t(bufferView)];
    if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
        Fail(name + ": buffer view " + std::to_string(bufferView) + " has no valid buffer");
    const tinygltf::Buffer &buf = model_.buffers[size_t(bv.buffer)];
    // All in 64-bit with each term bounded by a size_t, so nothing can overflow.
    const uint64_t viewEnd = uint64_t(bv.byteOffset) + uint64_t(bv.byteLength);
    if (bv.byteOffset > buf.data.size() || viewEnd > buf.data.size())
        Fail(name + ": buffer view " + std::to_string(bufferView) + " reaches past the end of " +
             "its buffer (" + std::to_string(viewEnd) + " > " + std::to_string(buf.data.size()) +
             " bytes)");
    if (byteOffset > bv.byteLength || bytes > bv.byteLength - byteOffset)
        Fail(name + ": " + role + " reaches past the end of its buffer view (" +
             std::to_string(byteOffset) + " + " + std::to_string(bytes) + " > " +
             std::to_string(bv.byteLength) + " bytes)");
    return buf.data.data() + bv.byteOffset + byteOffset;
}

// glTF 2.0 §3.6.2.3: `count` elements replace the base's at strictly increasing indices below
// the accessor's count; indices and values are tightly packed in their buffer views.
void GltfConverter::ApplySparse(const tinygltf::Accessor &a, const std::string &name,
                                uint64_t elemSize, std::vector<unsigned char> &elements) {
    const auto &sp = a.sparse;
    const Where where(*this, where_ + "/sparse");
    if (sp.count < 1 || uint64_t(sp.count) > uint64_t(a.count))
        Fail(name + ": sparse count " + std::to_string(sp.count) + " is not 1 to the accessor's " +
             std::to_string(a.count));
    const int type = sp.indices.componentType;
    const int isz = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                    : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                    : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                     : 0;
    if (isz == 0) Fail(name + ": sparse indices must be unsigned byte, short or int");
    const uint64_t count = uint64_t(sp.count);
    const unsigned char *indices =
        ViewBytes(sp.indices.bufferView, uint64_t(std::max(sp.indices.byteOffset, 0)),
                  count * uint64_t(isz), name, "its sparse indices");
    const unsigned char *values =
        ViewBytes(sp.values.bufferView, uint64_t(std::max(sp.values.byteOffset, 0)),
                  count * elemSize, name, "its sparse values");
    uint64_t previous = 0;
    for (uint64_t k = 0; k < count; ++k) {
        uint64_t index = 0;
        if (isz == 1) {
            index = indices[k];
        } else if (isz == 2) {
            uint16_t x;
            std::memcpy(&x, indices + 2 * k, 2);
            index = x;
        } else {
            uint32_t x;
            std::memcpy(&x, indices + 4 * k, 4);
            index = x;
        }
        if (index >= uint64_t(a.count))
            Fail(name + ": sparse index " + std::to_string(index) + " is out of range (" +
                 std::to_string(a.count) + " elements)");
        if (k > 0 && index <= previous)
            Fail(name + ": sparse indices must increase strictly (" + std::to_string(index) +
                 " follows " + std::to_string(previous) + ")");
        previous = index;
        std::memcpy(elements.data() + index * elemSize, values + k * elemSize, size_t(elemSize));
    }
}

AccessorView GltfConverter::View(int index, const std::string &what) {
    if (index < 0 || size_t(index) >= model_.accessors.size())
        Fail(what + " refers to accessor " + std::to_string(index) + ", which does not exist");
    const Where where(*this, "/accessors/" + std::to_string(index));
    const tinygltf::Accessor &a = model_.accessors[size_t(index)];
    std::string name = "accessor " + std::to_string(index) + " (" + what + ")";
    AccessorView v;
    v.componentType = a.componentType;
    v.components = ComponentCount(a.type);
    v.normalized = a.normalized;
    v.count = a.count;
    int cs = ComponentSize(a.componentType);
    if (cs == 0 || v.components == 0) Fail(name + " has an invalid type");
    if (a.count == 0) return v;
    const uint64_t elemSize = uint64_t(cs) * uint64_t(v.components);
    if (a.bufferView >= 0) {
        if (size_t(a.bufferView) >= model_.bufferViews.size())
            Fail(name + " has no valid buffer view");
        const tinygltf::BufferView &bv = model_.bufferViews[size_t(a.bufferView)];
        uint64_t stride = bv.byteStride ? bv.byteStride : elemSize;
        if (stride < elemSize)
            Fail(name + ": byteStride " + std::to_string(stride) +
                 " is smaller than the element size " + std::to_string(elemSize));
        if (a.byteOffset > bv.byteLength ||
            (a.count > 1 && stride > bv.byteLength / (uint64_t(a.count) - 1)))
            Fail(name + " reaches past the end of its buffer view");
        v.data = ViewBytes(a.bufferView, a.byteOffset, stride * (uint64_t(a.count) - 1) + elemSize,
                           name, "the accessor");
        v.stride = size_t(stride);
        if (!a.sparse.isSparse) return v;
    }
    // No buffer view (zeros, glTF 2.0 §3.6.2.3) or a sparse accessor: the elements made whole,
    // tightly packed, within the memory budget.
    if (uint64_t(a.count) > (uint64_t(1) << 40) / elemSize)
        Fail(name + " has too many elements (" + std::to_string(a.count) + ")");
    const uint64_t bytes = uint64_t(a.count) * elemSize;
    if (budget_) budget_->Check(bytes, name, loc_);
    auto elements = std::make_shared<std::vector<unsigned char>>(size_t(bytes));
    if (v.data)
        for (size_t i = 0; i < v.count; ++i)
            std::memcpy(elements->data() + i * elemSize, v.data + i * v.stride, size_t(elemSize));
    if (a.sparse.isSparse) ApplySparse(a, name, elemSize, *elements);
    v.data = elements->data();
    v.stride = size_t(elemSize);
    v.owned = std::move(elements);
    return v;
}

void GltfConverter::CheckAttributeType(const AccessorView &v, AttributeKind kind,
                                       const std::string &what) {
    const int t = v.componentType;
    if (t == TINYGLTF_COMPONENT_TYPE_FLOAT) return;
    const bool unsignedSmall =
        t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    const bool signedSmall =
        t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_SHORT;
    bool core = false, quantized = false;  // allowed by glTF 2.0 itself, by the extension
    switch (kind) {
        case AttributeKind::Position:
            quantized = unsignedSmall || signedSmall;
            break;
        case AttributeKind::Direction:
            quantized = signedSmall && v.normalized;
            break;
        case AttributeKind::TexCoord:
            core = unsignedSmall && v.normalized;
            quantized = unsignedSmall || signedSmall;
            break;
    }
    if (core || (quantized && quantization_)) return;
    const char *allowed =
        kind == AttributeKind::TexCoord ? "float or normalized unsigned byte/short" : "float";
    Fail(what + " accessor must have " + allowed + " components" +
         (quantized ? " (these need KHR_mesh_quantization in extensionsUsed)" : ""));
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

std::vector<Vec3f> GltfConverter::ReadVec3(int accessor, const std::string &what,
                                           AttributeKind kind) {
    AccessorView v = View(accessor, what);
    const Where where(*this, "/accessors/" + std::to_string(accessor));
    if (v.components != 3) Fail(what + " accessor must be VEC3");
    CheckAttributeType(v, kind, what);
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
    CheckAttributeType(v, AttributeKind::TexCoord, name);
    std::vector<Vec2f> out(v.count);
    // glTF's texture origin is the top-left corner, pbrt's (and Prism's) the bottom-left.
    for (size_t i = 0; i < v.count; ++i) {
        out[i] = Vec2f(float(Component(v, i, 0)), float(1.0 - Component(v, i, 1)));
        if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y))
            Fail(name + " accessor contains a value that is not a finite number");
    }
    return out;
}

// glTF 2.0 §3.7.2.2: each target i displaces the attributes it names by weight_i times its
// values (weights beyond the list are 0). Targets' POSITION and NORMAL are read as the
// attributes are (quantized types with KHR_mesh_quantization), TANGENT is not morphed.
void GltfConverter::ApplyMorphTargets(const tinygltf::Primitive &prim,
                                      const std::vector<double> &weights, std::vector<Vec3f> &P,
                                      std::vector<Vec3f> &N) {
    for (size_t i = 0; i < prim.targets.size() && i < weights.size(); ++i) {
        const float w = float(weights[i]);
        if (!std::isfinite(w)) Fail("morph target weight " + std::to_string(i) + " is not finite");
        if (w == 0) continue;
        const std::map<std::string, int> &target = prim.targets[i];
        const std::string name = "morph target " + std::to_string(i);
        for (auto [attribute, values, kind] :
             {std::tuple{"POSITION", &P, AttributeKind::Position},
              std::tuple{"NORMAL", &N, AttributeKind::Direction}}) {
            auto it = target.find(attribute);
            if (it == target.end() || values->empty()) continue;
            const std::vector<Vec3f> d = ReadVec3(it->second, name + " " + attribute, kind);
            if (d.size() != values->size())
                Fail(name + " " + attribute + " and the primitive's differ in count");
            for (size_t v = 0; v < d.size(); ++v) (*values)[v] += d[v] * w;
        }
    }
    for (Vec3f &n : N)
        if (LengthSquared(n) > 0) n = Normalize(n);
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
