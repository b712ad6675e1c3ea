// Bump and normal mapping: the shading normal moved by pbrt-v3's "bumpmap" displacement
// (Material::Bump) or by a tangent-space normal map, before the hit is shaded.
#include <cmath>

#include "render/material.h"

namespace prism {

namespace {

// pbrt-v3 Material::Bump without ray differentials: its fallback step du = dv = .0005 (pbrt
// takes .5 (|dudx| + |dudy|) and uses .0005 when that is 0). The displaced tangents leave out
// the displacement times the normal's derivatives (d dndu, d dndv): hits carry no dndu/dndv,
// and fetching the shape's curvature (Accel::NormalDerivatives) at every bumped hit would
// change every bump-mapped image; the term vanishes on flat surfaces and where the
// displacement is 0. Specular ray differentials at a bumped hit read the surface's own normal
// derivatives (render/differentials.h), as pbrt-v3 keeps the unbumped dndu/dndv there.
void Bump(const Texture &d, SurfaceInteraction &si) {
    constexpr float du = .0005f, dv = .0005f;
    const Vec3f n = si.ns;
    const TextureContext at = SurfaceTextureContext(si);
    TextureContext atU = at, atV = at;
    atU.uv = at.uv + Vec2f(du, 0);
    atU.p += si.dpdu * du;
    atV.uv = at.uv + Vec2f(0, dv);
    atV.p += si.dpdv * dv;
    const float displace = d.Evaluate(at).r;
    const float uDisplace = d.Evaluate(atU).r;
    const float vDisplace = d.Evaluate(atV).r;
    const Vec3f dpdu = si.dpdu + n * ((uDisplace - displace) / du);
    const Vec3f dpdv = si.dpdv + n * ((vDisplace - displace) / dv);
    Vec3f ns = Cross(dpdu, dpdv);
    const float len = Length(ns);
    if (!(len > 0) || !std::isfinite(len)) return;
    ns = ns / len;
    // pbrt's SetShadingGeometry(..., false): the shading normal turns to the geometric side.
    // (Cross(dpdu, dpdv) points along the unperturbed normal or against it with the
    // parameterization's handedness; orient it by the unperturbed shading normal first.)
    if (Dot(Cross(si.dpdu, si.dpdv), n) < 0) ns = -ns;
    si.ns = FaceForward(ns, si.n);
    si.dpdu = dpdu;
    si.dpdv = dpdv;
}

// A tangent-space normal map (glTF's convention: x along the tangent dp/du, y along the
// bitangent dp/dv, z along the shading normal; texel values c map to 2c - 1, and x and y are
// multiplied by the scale). The tangent is si.dpdu (a mesh's interpolated per-vertex tangent,
// TriangleMesh::GenerateTangents, else the parameterization's), made orthogonal to ns; the
// bitangent is ns x tangent, on dpdv's side.
void NormalMap(const Texture &map, float scale, SurfaceInteraction &si) {
    const Vec3f n = si.ns;
    Vec3f t = si.dpdu - n * Dot(n, si.dpdu);
    float tl = Length(t);
    Vec3f b;
    if (tl > 0 && std::isfinite(tl)) {
        t = t / tl;
        b = Cross(n, t);
        if (Dot(b, si.dpdv) < 0) b = -b;
    } else {
        CoordinateSystem(n, &t, &b);
    }
    const RGB c = map.Evaluate(SurfaceTextureContext(si));
    const Vec3f m((2 * c.r - 1) * scale, (2 * c.g - 1) * scale, 2 * c.b - 1);
    Vec3f ns = t * m.x + b * m.y + n * m.z;
    const float len = Length(ns);
    if (!(len > 0) || !std::isfinite(len)) return;
    ns = ns / len;
    si.ns = FaceForward(ns, si.n);
    // The tangent frame follows: dpdu made orthogonal to the new normal.
    si.dpdu = t - si.ns * Dot(si.ns, t);
    si.dpdv = Cross(si.ns, si.dpdu);
    if (Dot(si.dpdv, b) < 0) si.dpdv = -si.dpdv;
}

}  // namespace

void Material::PerturbShading(SurfaceInteraction &si) const {
    if (normalMap) NormalMap(*normalMap, normalScale, si);
    if (bump) Bump(*bump, si);
}

}  // namespace prism
