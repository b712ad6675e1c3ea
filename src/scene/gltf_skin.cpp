// glTF skins in their default pose (glTF 2.0 §3.7.3): each joint's matrix is its node's world
// matrix from the nodes' rest transforms times its inverse bind matrix, and each vertex moves
// by the weighted sum of its joints' matrices (linear blend skinning), normals by that sum's
// inverse transpose. Animations are not read: the rest transforms are the pose.
#include <cmath>
#include <utility>

#include "scene/gltf_converter.h"

namespace prism::gltf_internal {

namespace {

// The 3x3 cofactor matrix of m's upper-left block: det(m) times its inverse transpose.
void Cofactor(const Matrix4 &m, double c[3][3]) {
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) {
            const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
            c[r][k] = m.m[r1][k1] * m.m[r2][k2] - m.m[r1][k2] * m.m[r2][k1];
        }
}

}  // namespace

void GltfConverter::ApplySkin(int skinIndex, const tinygltf::Primitive &prim, std::vector<Vec3f> &P,
                              std::vector<Vec3f> &N, std::vector<Matrix4> *frames) {
    if (skinIndex < 0 || size_t(skinIndex) >= model_.skins.size())
        Fail("node refers to skin " + std::to_string(skinIndex) + ", which does not exist");
    const tinygltf::Skin &skin = model_.skins[size_t(skinIndex)];
    const Where where(*this, "/skins/" + std::to_string(skinIndex));
    const size_t nJoints = skin.joints.size();
    if (nJoints == 0) Fail("skin has no joints");
    // The joints' matrices.
    std::vector<Matrix4> joint(nJoints, Matrix4::Identity());
    AccessorView ibm;
    if (skin.inverseBindMatrices >= 0) {
        ibm = View(skin.inverseBindMatrices, "inverseBindMatrices");
        if (ibm.components != 16 || ibm.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            Fail("inverseBindMatrices accessor must be MAT4 of floats");
        if (ibm.count < nJoints)
            Fail("inverseBindMatrices has " + std::to_string(ibm.count) + " matrices for " +
                 std::to_string(nJoints) + " joints");
    }
    for (size_t j = 0; j < nJoints; ++j) {
        Matrix4 inverseBind = Matrix4::Identity();
        if (ibm.count)
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) {
                    inverseBind.m[r][c] = Component(ibm, j, c * 4 + r);  // column-major
                    if (!std::isfinite(inverseBind.m[r][c]))
                        Fail("inverseBindMatrices contains a value that is not a finite number");
                }
        joint[j] = NodeWorldMatrix(skin.joints[j]) * inverseBind;
    }
    // Each vertex's blend of its joints' matrices, from JOINTS_n and WEIGHTS_n.
    std::vector<Matrix4> blend(P.size());  // zero
    std::vector<double> total(P.size(), 0.0);
    for (int set = 0;; ++set) {
        const std::string js = "JOINTS_" + std::to_string(set),
                          ws = "WEIGHTS_" + std::to_string(set);
        auto jt = prim.attributes.find(js), wt = prim.attributes.find(ws);
        if (jt == prim.attributes.end() || wt == prim.attributes.end()) {
            if (set == 0) Fail("a skinned primitive needs JOINTS_0 and WEIGHTS_0");
            break;
        }
        const AccessorView jv = View(jt->second, js), wv = View(wt->second, ws);
        if (jv.components != 4 || (jv.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                   jv.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
            Fail(js + " accessor must be VEC4 of unsigned bytes or shorts");
        const bool wOk =
            wv.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
            (wv.normalized && (wv.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                               wv.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
        if (wv.components != 4 || !wOk)
            Fail(ws + " accessor must be VEC4 of floats or normalized unsigned bytes or shorts");
        if (jv.count != P.size() || wv.count != P.size())
            Fail(js + " and " + ws + " must have one element per vertex");
        for (size_t v = 0; v < P.size(); ++v)
            for (int k = 0; k < 4; ++k) {
                const double w = Component(wv, v, k);
                if (!std::isfinite(w) || w < 0)
                    Fail(ws + " contains a weight that is negative or not a finite number");
                if (w == 0) continue;
                const double j = Component(jv, v, k);
                if (j >= double(nJoints))
                    Fail(js + " names joint " + std::to_string(uint64_t(j)) + " of a skin of " +
                         std::to_string(nJoints));
                const Matrix4 &m = joint[size_t(j)];
                for (int r = 0; r < 4; ++r)
                    for (int c = 0; c < 4; ++c) blend[v].m[r][c] += w * m.m[r][c];
                total[v] += w;
            }
        if (set >= 7) break;
    }
    for (size_t v = 0; v < P.size(); ++v) {
        Matrix4 &m = blend[v];
        if (!(total[v] > 0)) {
            m = Matrix4::Identity();  // no weight: the vertex stays where it is
            continue;
        }
        for (auto &row : m.m)
            for (double &x : row) x /= total[v];  // weights normally sum to one already
        const Vec3f p = P[v];
        P[v] = Vec3f(float(m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3]),
                     float(m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3]),
                     float(m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3]));
        if (!N.empty()) {
            double c[3][3];
            Cofactor(m, c);
            const Vec3f n = N[v];
            Vec3f out(float(c[0][0] * n.x + c[0][1] * n.y + c[0][2] * n.z),
                      float(c[1][0] * n.x + c[1][1] * n.y + c[1][2] * n.z),
                      float(c[2][0] * n.x + c[2][1] * n.y + c[2][2] * n.z));
            if (m.Determinant3x3() < 0) out = -out;
            if (LengthSquared(out) > 0) N[v] = Normalize(out);
        }
    }
    if (frames) *frames = std::move(blend);
}

}  // namespace prism::gltf_internal
