// CSG by interval combination along the ray (Roth 1982): each operand's crossings, normalized
// to alternate entry/exit, are merged in t order and the boolean operation is re-evaluated at
// every crossing; where its value changes, the result has a boundary.
#include "geometry/csg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <stdexcept>
#include <tuple>

#include "geometry/accel.h"

namespace prism {

bool ParseCsgOp(const std::string &name, CsgOp *op) {
    if (name == "union")
        *op = CsgOp::Union;
    else if (name == "intersection")
        *op = CsgOp::Intersection;
    else if (name == "difference")
        *op = CsgOp::Difference;
    else
        return false;
    return true;
}

const char *CsgOpName(CsgOp op) {
    switch (op) {
        case CsgOp::Union:
            return "union";
        case CsgOp::Intersection:
            return "intersection";
        case CsgOp::Difference:
            break;
    }
    return "difference";
}

std::string MeshClosedError(const TriangleMesh &mesh) {
    if (mesh.NumTriangles() == 0) return "the mesh has no triangles";
    // Weld vertices by exact position: meshes often split vertices for normals or uv.
    std::map<std::tuple<float, float, float>, uint32_t> ids;
    std::vector<uint32_t> weld(mesh.NumVertices());
    for (uint32_t i = 0; i < mesh.NumVertices(); ++i) {
        Vec3f p = mesh.Position(i);
        weld[i] = ids.emplace(std::make_tuple(p.x, p.y, p.z), uint32_t(ids.size())).first->second;
    }
    std::map<std::pair<uint32_t, uint32_t>, int> edges;  // welded edge -> triangles using it
    for (size_t t = 0; t < mesh.NumTriangles(); ++t) {
        const uint32_t *v = mesh.Triangle(t);
        for (int e = 0; e < 3; ++e) {
            uint32_t a = weld[v[e]], b = weld[v[(e + 1) % 3]];
            if (a == b) continue;  // degenerate edge of a degenerate triangle
            edges[{std::min(a, b), std::max(a, b)}]++;
        }
    }
    for (const auto &[key, count] : edges) {
        if (count == 2) continue;
        // Report the edge by its endpoints' positions (render space).
        Vec3f pa, pb;
        for (uint32_t i = 0; i < mesh.NumVertices(); ++i) {
            if (weld[i] == key.first) pa = mesh.Position(i);
            if (weld[i] == key.second) pb = mesh.Position(i);
        }
        auto str = [](Vec3f p) {
            char buf[96];
            std::snprintf(buf, sizeof(buf), "(%g %g %g)", double(p.x), double(p.y), double(p.z));
            return std::string(buf);
        };
        return "the mesh is not closed: edge " + str(pa) + "-" + str(pb) + " belongs to " +
               std::to_string(count) + (count == 1 ? " triangle" : " triangles") +
               " (every edge must belong to exactly 2)";
    }
    return "";
}

// One crossing of a solid's boundary. `entering` is the solid's (the list's), `leafEntering`
// the operand surface's own: they differ where the surface is carved (its normal flips).
struct CsgShape::Crossing {
    double t;
    bool entering, leafEntering;
    int leaf;
    ObjectHit hit;  // analytic leaves: the leaf's object-space hit
    int prim;       // mesh leaves: the triangle
    float u, v;     // mesh leaves: Embree's barycentrics
};

// A solid along the ray: inside at tMin or not, then crossings that alternate strictly and
// leave it outside after the last one.
struct CsgShape::List {
    bool insideAtStart = false;
    std::vector<Crossing> c;
    // Merging state in Gather: the next crossing to take, and whether the ray is inside.
    size_t next = 0;
    bool inside = false;
};

namespace {

// Per-thread scratch lists, so that a CSG ray allocates nothing once the lists have grown to
// the scene's needs: Gather takes one list per operand and gives them back on return. A deque
// keeps references valid while nested nodes take more.
struct CsgScratch {
    std::deque<CsgShape::List> lists;
    size_t used = 0;
};
thread_local CsgScratch csgScratch;

// Takes n consecutive lists (cleared) for the current call; returns them when it goes.
class ScratchLists {
  public:
    explicit ScratchLists(size_t n) : base_(csgScratch.used) {
        CsgScratch &s = csgScratch;
        while (s.lists.size() < base_ + n) s.lists.emplace_back();
        for (size_t i = base_; i < base_ + n; ++i) {
            CsgShape::List &l = s.lists[i];
            l.c.clear();
            l.insideAtStart = l.inside = false;
            l.next = 0;
        }
        s.used = base_ + n;
    }
    ~ScratchLists() { csgScratch.used = base_; }
    ScratchLists(const ScratchLists &) = delete;
    ScratchLists &operator=(const ScratchLists &) = delete;
    CsgShape::List &operator[](size_t i) const { return csgScratch.lists[base_ + i]; }

  private:
    size_t base_;
};

}  // namespace

struct CsgShape::Leaf {
    Bounds3d bounds;  // render space, padded
    std::unique_ptr<AnalyticShape> analytic;
    std::unique_ptr<Accel> meshScene;  // holds the mesh (shape 0)
    const TriangleMesh *mesh = nullptr;
    float outward = 1;  // +1 if the mesh's geometric normals point out of the solid
};

CsgShape::CsgShape() : AnalyticShape(Transform(), false) {}
CsgShape::~CsgShape() = default;

int CsgShape::AddLeaf(std::unique_ptr<AnalyticShape> shape) {
    auto leaf = std::make_unique<Leaf>();
    leaf->analytic = std::move(shape);
    leaves_.push_back(std::move(leaf));
    return int(leaves_.size()) - 1;
}

int CsgShape::AddLeaf(std::unique_ptr<TriangleMesh> mesh) {
    auto leaf = std::make_unique<Leaf>();
    // Orientation from the signed volume: the operand is the enclosed solid whichever way
    // its triangles wind.
    double volume = 0;
    for (size_t t = 0; t < mesh->NumTriangles(); ++t) {
        const uint32_t *v = mesh->Triangle(t);
        Vec3d p0(mesh->Position(v[0])), p1(mesh->Position(v[1])), p2(mesh->Position(v[2]));
        Vec3d n = Cross(p1 - p0, p2 - p0);
        if (mesh->FlipNormals()) n = -n;
        volume += Dot(p0, n);
    }
    leaf->outward = volume < 0 ? -1.f : 1.f;
    leaf->mesh = mesh.get();
    AccelOptions options;
    options.robust = true;  // watertight: a ray through an edge must not slip between triangles
    leaf->meshScene = std::make_unique<Accel>(options);
    leaf->meshScene->AddMesh(std::move(mesh));
    leaves_.push_back(std::move(leaf));
    return int(leaves_.size()) - 1;
}

int CsgShape::AddNode(CsgOp op, std::vector<CsgRef> operands) {
    if (operands.empty()) throw std::invalid_argument("a CSG node needs at least one operand");
    nodes_.push_back({op, std::move(operands)});
    return int(nodes_.size()) - 1;
}

Bounds3d CsgShape::BoundsOf(const CsgRef &ref) const {
    if (ref.leaf) {
        const Leaf &l = *leaves_[size_t(ref.index)];
        Bounds3f b = l.analytic ? l.analytic->RenderBounds() : l.mesh->RenderBounds();
        return Bounds3d(Vec3d(b.pMin), Vec3d(b.pMax));
    }
    const Node &n = nodes_[size_t(ref.index)];
    Bounds3d b = BoundsOf(n.operands[0]);
    if (n.op == CsgOp::Difference) return b;
    for (size_t i = 1; i < n.operands.size(); ++i) {
        Bounds3d o = BoundsOf(n.operands[i]);
        if (n.op == CsgOp::Union) {
            b.Expand(o);
        } else {
            b.pMin = Max(b.pMin, o.pMin);
            b.pMax = Min(b.pMax, o.pMax);
        }
    }
    if (b.IsEmpty()) {  // an intersection of disjoint boxes is empty: a point box, never hit
        Vec3d c = BoundsOf(n.operands[0]).Center();
        b = Bounds3d(c, c);
    }
    return b;
}

void CsgShape::Finish() {
    if (nodes_.empty()) throw std::invalid_argument("a CSG shape needs a node");
    for (auto &l : leaves_) {
        if (l->meshScene) l->meshScene->Commit();
        Bounds3f b = l->analytic ? l->analytic->RenderBounds() : l->mesh->RenderBounds();
        // Padded again: the slab test below runs in double on float rays.
        Vec3d pad = (Abs(Vec3d(b.pMin)) + Abs(Vec3d(b.pMax))) * 1e-6 + Vec3d(1e-30, 1e-30, 1e-30);
        l->bounds = Bounds3d(Vec3d(b.pMin) - pad, Vec3d(b.pMax) + pad);
    }
    bounds_ = BoundsOf({false, NumNodes() - 1});
}

double CsgShape::ImplicitOf(const CsgRef &ref, const Vec3d &p) const {
    if (ref.leaf) {
        const Leaf &l = *leaves_[size_t(ref.index)];
        if (!l.analytic) return 0;
        return l.analytic->Implicit(l.analytic->ObjectFromRender<double>().Point(p));
    }
    const Node &n = nodes_[size_t(ref.index)];
    double f = ImplicitOf(n.operands[0], p);
    for (size_t i = 1; i < n.operands.size(); ++i) {
        double g = ImplicitOf(n.operands[i], p);
        f = n.op == CsgOp::Union ? std::min(f, g)
                                 : std::max(f, n.op == CsgOp::Intersection ? g : -g);
    }
    return f;
}

double CsgShape::Implicit(const Vec3d &p) const { return ImplicitOf({false, NumNodes() - 1}, p); }

Vec3d CsgShape::ImplicitGradient(const Vec3d &p) const {
    // Central differences of the combined function (tests only).
    double h = 1e-6 * std::max(1.0, MaxComponent(Abs(p)));
    Vec3d g;
    for (int i = 0; i < 3; ++i) {
        Vec3d a = p, b = p;
        a[i] += h;
        b[i] -= h;
        g[i] = (Implicit(a) - Implicit(b)) / (2 * h);
    }
    return g;
}

// Makes a leaf's raw crossings alternate (a repeated entry, e.g. a ray through an edge shared
// by two triangles, is one entry) and end outside: a bounded solid cannot be entered for good,
// so a trailing entry (a grazing ray that found one of two coincident roots, or an open
// surface) closes at once.
static void NormalizeList(CsgShape::List *list) {
    std::vector<CsgShape::Crossing> &c = list->c;
    if (c.empty()) return;
    list->insideAtStart = !c[0].entering;
    bool inside = list->insideAtStart;
    size_t n = 0;
    for (size_t i = 0; i < c.size(); ++i) {
        if (c[i].entering == inside) continue;
        inside = c[i].entering;
        c[n++] = c[i];
    }
    c.resize(n);
    if (inside) {
        CsgShape::Crossing exit = c.back();
        exit.entering = exit.leafEntering = false;
        c.push_back(exit);
    }
}

// Whether the ray (t > tMin) can meet the box: most operands of a big CSG tree (the pips of a
// die) lie off most rays, and the slab test is far cheaper than their root routines.
static bool RayMeetsBox(const Bounds3d &b, const Vec3f &o, const Vec3f &d, float tMin) {
    double t0 = tMin, t1 = Infinity;
    for (int i = 0; i < 3; ++i) {
        double inv = 1 / double(d[i]);
        double tNear = (b.pMin[i] - double(o[i])) * inv, tFar = (b.pMax[i] - double(o[i])) * inv;
        if (tNear > tFar) std::swap(tNear, tFar);
        if (std::isnan(tNear) || std::isnan(tFar)) continue;  // 0 * inf: o on a slab plane
        t0 = std::max(t0, tNear);
        t1 = std::min(t1, tFar);
        if (t0 > t1) return false;
    }
    return true;
}

void CsgShape::GatherLeaf(int index, const Vec3f &o, const Vec3f &d, float tMin,
                          Precision precision, List *out) const {
    const Leaf &l = *leaves_[size_t(index)];
    if (!RayMeetsBox(l.bounds, o, d, tMin)) return;
    // Analytic shapes have at most 4 roots (the torus); meshes are bounded by a generous cap
    // so a degenerate mesh cannot stall a ray.
    const int maxCrossings = l.analytic ? 8 : 4096;
    float t0 = tMin;
    for (int k = 0; k < maxCrossings; ++k) {
        Crossing c{};
        c.leaf = index;
        if (l.analytic) {
            if (!l.analytic->Intersect(o, d, t0, Infinity, precision, &c.hit)) break;
            c.t = c.hit.t;
            Vec3d dObj = l.analytic->ObjectFromRender<double>().Vector(Vec3d(d));
            c.entering = Dot(l.analytic->ImplicitGradient(c.hit.p), dObj) < 0;
            // Resume just past this root: the root routine never returns t <= its tMin.
            float tf = float(c.t);
            t0 = tf > c.t ? tf : NextFloatUp(tf);
        } else {
            RawHit h;
            Ray ray{o, d, Infinity, t0};
            if (!l.meshScene->IntersectRaw(ray, &h)) break;
            c.t = h.t;
            c.prim = h.prim;
            c.u = h.u;
            c.v = h.v;
            Vec3f n = l.mesh->GeometricNormal(size_t(h.prim)) * l.outward;
            float cosine = Dot(n, d);
            // A few ulps past the hit: Embree's tnear test is done before its division.
            t0 = NextFloatUp(NextFloatUp(NextFloatUp(NextFloatUp(h.t))));
            if (cosine == 0) continue;  // edge-on triangle: no crossing
            c.entering = cosine < 0;
        }
        c.leafEntering = c.entering;
        out->c.push_back(c);
    }
    NormalizeList(out);
}

void CsgShape::Gather(const CsgRef &ref, const Vec3f &o, const Vec3f &d, float tMin,
                      Precision precision, List *out) const {
    if (ref.leaf) return GatherLeaf(ref.index, o, d, tMin, precision, out);
    const Node &node = nodes_[size_t(ref.index)];
    const size_t n = node.operands.size();
    ScratchLists lists(n);
    for (size_t i = 0; i < n; ++i) {
        Gather(node.operands[i], o, d, tMin, precision, &lists[i]);
        // An intersection with, or a difference from, a solid the ray never meets is empty.
        bool empty = lists[i].c.empty() && !lists[i].insideAtStart;
        if (empty && (node.op == CsgOp::Intersection || (node.op == CsgOp::Difference && i == 0)))
            return;
    }
    auto evaluate = [&] {
        switch (node.op) {
            case CsgOp::Union:
                for (size_t i = 0; i < n; ++i)
                    if (lists[i].inside) return true;
                return false;
            case CsgOp::Intersection:
                for (size_t i = 0; i < n; ++i)
                    if (!lists[i].inside) return false;
                return true;
            case CsgOp::Difference:
                break;
        }
        if (!lists[0].inside) return false;
        for (size_t i = 1; i < n; ++i)
            if (lists[i].inside) return false;
        return true;
    };
    for (size_t i = 0; i < n; ++i) lists[i].inside = lists[i].insideAtStart;
    bool inside = evaluate();
    out->insideAtStart = inside;
    // Merge in t order; ties keep operand order.
    for (;;) {
        size_t best = n;
        for (size_t i = 0; i < n; ++i) {
            const List &l = lists[i];
            if (l.next < l.c.size() &&
                (best == n || l.c[l.next].t < lists[best].c[lists[best].next].t))
                best = i;
        }
        if (best == n) break;
        List &l = lists[best];
        const Crossing &c = l.c[l.next++];
        l.inside = c.entering;
        bool now = evaluate();
        if (now == inside) continue;
        inside = now;
        Crossing r = c;
        r.entering = now;
        out->c.push_back(r);
    }
}

std::vector<std::pair<double, bool>> CsgShape::Crossings(const Vec3f &o, const Vec3f &d, float tMin,
                                                         Precision precision) const {
    ScratchLists top(1);
    List &list = top[0];
    Gather({false, NumNodes() - 1}, o, d, tMin, precision, &list);
    std::vector<std::pair<double, bool>> r;
    for (const Crossing &c : list.c) r.push_back({c.t, c.entering});
    return r;
}

bool CsgShape::Intersect(const Vec3f &o, const Vec3f &d, float tMin, float tMax,
                         Precision precision, ObjectHit *hit) const {
    // Crossings are gathered from tMin to infinity whatever tMax is, so the closest-hit
    // callback and phase 2 (which sees the ray's original tMax) find the same hit.
    ScratchLists top(1);
    List &list = top[0];
    Gather({false, NumNodes() - 1}, o, d, tMin, precision, &list);
    for (const Crossing &c : list.c) {
        if (!(c.t > double(tMin))) continue;
        if (!(c.t < double(tMax))) return false;
        const Leaf &l = *leaves_[size_t(c.leaf)];
        hit->t = c.t;
        hit->part = c.leaf;
        hit->partFlip = c.entering != c.leafEntering;
        if (l.analytic) {
            const Transform &m = l.analytic->RenderFromObject();
            hit->p = m.Point(c.hit.p);
            hit->pError = m.PointError(c.hit.p, c.hit.pError, MachineEpsilon<double>());
            hit->phi = c.hit.phi;
        } else {
            SurfaceInteraction si =
                l.mesh->Interaction(size_t(c.prim), c.u, c.v, float(c.t), d, NeedNone);
            hit->p = Vec3d(si.p);
            hit->pError = Vec3d(si.pError);
            hit->partPrim = c.prim;
            hit->phi = 0;
        }
        return true;
    }
    return false;
}

void CsgShape::NormalDerivatives(const SurfaceInteraction &si, const Vec3f &n, const Vec3f *dp,
                                 Vec3f *dn, int count) const {
    const int part = si.instanceShape;
    if (part >= 0 && part < NumLeaves() && leaves_[size_t(part)]->analytic) {
        leaves_[size_t(part)]->analytic->NormalDerivatives(si, n, dp, dn, count);
        return;
    }
    for (int i = 0; i < count; ++i) dn[i] = Vec3f();
}

LocalGeometry CsgShape::Geometry(const ObjectHit &hit) const {
    LocalGeometry g;
    if (hit.part < 0 || hit.part >= NumLeaves()) {  // not a CSG hit (cannot happen)
        g.n = Vec3d(0, 0, 1);
        return g;
    }
    const Leaf &l = *leaves_[size_t(hit.part)];
    if (l.analytic) {
        const AnalyticShape &s = *l.analytic;
        const Transform &m = s.RenderFromObject();
        ObjectHit leafHit = hit;
        leafHit.p = s.ObjectFromRender<double>().Point(hit.p);
        LocalGeometry lg = s.Geometry(leafHit);
        g.dpdu = m.Vector(lg.dpdu);
        g.dpdv = m.Vector(lg.dpdv);
        g.uv = lg.uv;
        g.n = m.Normal(lg.n);
        // Out of the operand's solid, whatever ReverseOrientation or a mirroring transform did.
        if (Dot(g.n, m.Normal(s.ImplicitGradient(leafHit.p))) < 0) g.n = -g.n;
    } else {
        const TriangleMesh &mesh = *l.mesh;
        const uint32_t *v = mesh.Triangle(size_t(hit.partPrim));
        // Barycentrics of the hit point (Embree's u, v are not kept in ObjectHit).
        Vec3d p0(mesh.Position(v[0])), p1(mesh.Position(v[1])), p2(mesh.Position(v[2]));
        Vec3d e1 = p1 - p0, e2 = p2 - p0, w = hit.p - p0;
        double d11 = Dot(e1, e1), d12 = Dot(e1, e2), d22 = Dot(e2, e2);
        double w1 = Dot(w, e1), w2 = Dot(w, e2), den = d11 * d22 - d12 * d12;
        float b1 = den != 0 ? float((d22 * w1 - d12 * w2) / den) : 0.f;
        float b2 = den != 0 ? float((d11 * w2 - d12 * w1) / den) : 0.f;
        SurfaceInteraction si =
            mesh.Interaction(size_t(hit.partPrim), b1, b2, float(hit.t), Vec3f(0, 0, 1), NeedAll);
        g.dpdu = Vec3d(si.dpdu);
        g.dpdv = Vec3d(si.dpdv);
        g.uv = Vec2d(si.uv.x, si.uv.y);
        g.n = Vec3d(mesh.GeometricNormal(size_t(hit.partPrim)) * l.outward);
    }
    if (hit.partFlip) g.n = -g.n;
    return g;
}

}  // namespace prism
