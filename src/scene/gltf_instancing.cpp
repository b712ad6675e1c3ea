// EXT_mesh_gpu_instancing: a node whose mesh is drawn once per instance, each at the node's
// world transform times the instance's own translation, rotation and scale (per-instance
// accessors). The mesh becomes one ObjectDesc and each instance an InstanceDesc, so the
// renderer instances it (Embree instances) instead of copying it.
#include <cmath>

#include "scene/gltf_converter.h"

namespace prism::gltf_internal {

Matrix4 TrsMatrix(const double t[3], const double q[4], const double s[3]) {
    double len = 0;
    for (int i = 0; i < 4; ++i) len += q[i] * q[i];
    len = std::sqrt(len);
    const double d = len > 0 ? len : 1;  // a zero quaternion is the identity anyway
    const double x = q[0] / d, y = q[1] / d, z = q[2] / d, w = q[3] / d;
    const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    Matrix4 m = Matrix4::Identity();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m.m[r][c] = R[r][c] * s[c];
        m.m[r][3] = t[r];
    }
    return m;
}

void GltfConverter::AddMeshInstances(const tinygltf::Node &node, const Matrix4 &world) {
    const tinygltf::Value &ext = node.extensions.at("EXT_mesh_gpu_instancing");
    const Where where(*this, where_ + "/extensions/EXT_mesh_gpu_instancing");
    // (Get on anything but an object gives null: no attributes.)
    const tinygltf::Value &attributes = ext.Get("attributes");
    // Each attribute's accessor: TRANSLATION and SCALE floats, ROTATION floats or normalized
    // signed bytes or shorts (the extension's types), all of one count.
    struct Attribute {
        const char *name;
        int components;
        AccessorView view;
        bool present = false;
    };
    Attribute attrs[] = {{"TRANSLATION", 3, {}}, {"ROTATION", 4, {}}, {"SCALE", 3, {}}};
    size_t count = 0;
    bool any = false;
    for (Attribute &a : attrs) {
        const tinygltf::Value v = attributes.Get(a.name);
        if (!v.IsNumber() && !v.IsInt()) continue;
        const std::string what = std::string("instance ") + a.name;
        a.view = View(v.IsInt() ? v.Get<int>() : int(v.Get<double>()), what);
        a.present = true;
        const int t = a.view.componentType;
        const bool ok = t == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                        (a.components == 4 && a.view.normalized &&
                         (t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_SHORT));
        if (a.view.components != a.components || !ok)
            Fail(what + " accessor must be " + (a.components == 3 ? "VEC3" : "VEC4") +
                 " of floats" + (a.components == 4 ? " or normalized bytes or shorts" : ""));
        if (any && a.view.count != count)
            Fail("EXT_mesh_gpu_instancing attributes differ in count");
        count = a.view.count;
        any = true;
    }
    if (!any) Fail("EXT_mesh_gpu_instancing has no TRANSLATION, ROTATION or SCALE");
    // The instances' descriptions, charged before they are made.
    if (budget_)
        budget_->Check(uint64_t(count) * (sizeof(InstanceDesc) + 64),
                       std::to_string(count) + " mesh instances", loc_);
    // An emissive mesh is copied per instance: area lights are not instanced.
    const tinygltf::Mesh *mesh = node.mesh >= 0 && size_t(node.mesh) < model_.meshes.size()
                                     ? &model_.meshes[size_t(node.mesh)]
                                     : nullptr;
    bool emits = false;
    if (mesh)
        for (const tinygltf::Primitive &p : mesh->primitives)
            emits = emits || (p.material >= 0 && size_t(p.material) < areaLightOfMaterial_.size() &&
                              areaLightOfMaterial_[size_t(p.material)] >= 0);
    std::string object;
    if (!emits) {
        const std::pair<int, const tinygltf::Node *> key(node.mesh,
                                                         node.weights.empty() ? nullptr : &node);
        auto it = meshObjects_.find(key);
        if (it == meshObjects_.end()) {
            // The mesh in its own space, moved from the scene's shapes into an object.
            const size_t first = desc_.shapes.size();
            AddMesh(node.mesh, Transform(), node.weights);
            ObjectDesc o;
            o.name = "gltf:mesh" + std::to_string(node.mesh) + ":instances" +
                     (key.second ? ":" + std::to_string(meshObjects_.size()) : "");
            o.loc = loc_;
            for (size_t i = first; i < desc_.shapes.size(); ++i)
                o.shapes.push_back(std::move(desc_.shapes[i]));
            desc_.shapes.resize(first);
            desc_.objects.push_back(std::move(o));
            it = meshObjects_.emplace(key, desc_.objects.back().name).first;
        }
        object = it->second;
    }
    for (size_t k = 0; k < count; ++k) {
        double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
        double *out[] = {t, q, s};
        for (int a = 0; a < 3; ++a)
            if (attrs[a].present)
                for (int c = 0; c < attrs[a].components; ++c) {
                    out[a][c] = Component(attrs[a].view, k, c);
                    if (!std::isfinite(out[a][c]))
                        Fail(std::string("instance ") + attrs[a].name +
                             " accessor contains a value that is not a finite number");
                }
        Transform worldFromInstance;
        try {
            worldFromInstance = Transform(world * TrsMatrix(t, q, s));
        } catch (const std::invalid_argument &) {
            continue;  // a zero scale hides the instance
        }
        if (emits) {
            AddMesh(node.mesh, worldFromInstance, node.weights);
        } else {
            InstanceDesc inst;
            inst.object = object;
            inst.worldFromInstance = worldFromInstance;
            inst.loc = loc_;
            desc_.instances.push_back(std::move(inst));
        }
    }
}

}  // namespace prism::gltf_internal
