// Tangents for normal maps (geometry/triangle_mesh.h): generated from uv, or given.
#include <gtest/gtest.h>

#include <stdexcept>

#include "geometry/triangle_mesh.h"

namespace prism {
namespace {

// Tangents for normal maps (TriangleMesh::SetTangents / GenerateTangents): Interaction gives the
// interpolated tangent and bitangent as dpdu / dpdv.
std::unique_ptr<TriangleMesh> UvQuad(std::vector<Vec2f> uv) {
    std::vector<Vec3f> P = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
    std::vector<Vec3f> N(4, Vec3f(0, 0, 1));
    return std::make_unique<TriangleMesh>(Transform(), false, P,
                                          std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, N, uv);
}

void ExpectNear(const Vec3f &a, const Vec3f &b) {
    EXPECT_NEAR(a.x, b.x, 1e-6);
    EXPECT_NEAR(a.y, b.y, 1e-6);
    EXPECT_NEAR(a.z, b.z, 1e-6);
}

TEST(Tangents, GeneratedFromUv) {
    auto m = UvQuad({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    m->GenerateTangents();
    SurfaceInteraction si = m->Interaction(0, 0.3f, 0.2f, 1, Vec3f(0, 0, -1));
    ExpectNear(si.dpdu, Vec3f(1, 0, 0));
    ExpectNear(si.dpdv, Vec3f(0, 1, 0));
    // Mirrored u: the tangent turns round, the bitangent stays along +v.
    auto mirrored = UvQuad({{1, 0}, {0, 0}, {0, 1}, {1, 1}});
    mirrored->GenerateTangents();
    si = mirrored->Interaction(1, 0.3f, 0.2f, 1, Vec3f(0, 0, -1));
    ExpectNear(si.dpdu, Vec3f(-1, 0, 0));
    ExpectNear(si.dpdv, Vec3f(0, 1, 0));
}

TEST(Tangents, GivenWithTheirSignAndTransformed) {
    // glTF TANGENT (0, 1, 0, -1): bitangent = w (n x t) = -(z x y) = +x.
    auto m = UvQuad({});
    m->SetTangents(Transform(), {0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1});
    SurfaceInteraction si = m->Interaction(0, 0.3f, 0.2f, 1, Vec3f(0, 0, -1));
    ExpectNear(si.dpdu, Vec3f(0, 1, 0));
    ExpectNear(si.dpdv, Vec3f(1, 0, 0));
    EXPECT_THROW(m->SetTangents(Transform(), {0, 1, 0, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace prism
