#include "geometry/loop_subdiv.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace prism {

namespace {

using Face = std::array<int, 3>;

// Loop's vertex weight for an interior vertex of valence n (Warren's 3/16 for n = 3).
double Beta(int n) { return n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * n); }
// Weight of each neighbour in the limit-position mask of an interior vertex.
double Gamma(int n) { return 1.0 / (n + 3.0 / (8.0 * Beta(n))); }

// The edges of a triangle mesh and, per vertex, the sums its subdivision masks need.
struct Topology {
    std::vector<int> faceEdge;  // 3 per face: edge (f[i], f[i+1 mod 3])
    std::vector<std::array<int, 2>> edgeVerts;
    std::vector<std::array<int, 2>> edgeOpposite;  // opposite vertices of the first two faces
    std::vector<int> edgeFaces;                    // faces using the edge (2: interior)
    std::vector<int> valence, boundaryEdges;       // per vertex
    std::vector<Vec3d> neighbourSum, boundarySum;

    Topology(const std::vector<Vec3d> &p, const std::vector<Face> &faces) {
        size_t nf = faces.size();
        // Sorting (edge key, face-edge) pairs groups the uses of each edge without a hash map.
        std::vector<std::pair<uint64_t, uint32_t>> keys(nf * 3);
        for (size_t f = 0; f < nf; ++f)
            for (int i = 0; i < 3; ++i) {
                uint32_t a = uint32_t(faces[f][i]), b = uint32_t(faces[f][(i + 1) % 3]);
                keys[f * 3 + i] = {(uint64_t(std::min(a, b)) << 32) | std::max(a, b),
                                   uint32_t(f * 3 + i)};
            }
        std::sort(keys.begin(), keys.end());
        faceEdge.assign(nf * 3, -1);
        for (size_t i = 0; i < keys.size();) {
            size_t j = i;
            int e = int(edgeVerts.size());
            std::array<int, 2> opp{-1, -1};
            for (; j < keys.size() && keys[j].first == keys[i].first; ++j) {
                uint32_t fe = keys[j].second;
                faceEdge[fe] = e;
                if (j - i < 2) opp[j - i] = faces[fe / 3][(fe % 3 + 2) % 3];
            }
            edgeVerts.push_back({int(keys[i].first >> 32), int(keys[i].first & 0xffffffffu)});
            edgeOpposite.push_back(opp);
            edgeFaces.push_back(int(j - i));
            i = j;
        }
        valence.assign(p.size(), 0);
        boundaryEdges.assign(p.size(), 0);
        neighbourSum.assign(p.size(), Vec3d(0, 0, 0));
        boundarySum.assign(p.size(), Vec3d(0, 0, 0));
        for (size_t e = 0; e < edgeVerts.size(); ++e) {
            int a = edgeVerts[e][0], b = edgeVerts[e][1];
            valence[a]++;
            valence[b]++;
            neighbourSum[a] += p[b];
            neighbourSum[b] += p[a];
            if (edgeFaces[e] != 2) {  // a boundary, or a non-manifold edge treated as a crease
                boundaryEdges[a]++;
                boundaryEdges[b]++;
                boundarySum[a] += p[b];
                boundarySum[b] += p[a];
            }
        }
    }

    bool Interior(int v) const { return boundaryEdges[v] == 0 && valence[v] >= 3; }
    bool Boundary(int v) const { return boundaryEdges[v] == 2; }
};

// One level: even (old) vertices are smoothed, odd vertices are inserted on every edge, and
// every triangle becomes four with the same winding.
void Subdivide(std::vector<Vec3d> &p, std::vector<Face> &faces) {
    Topology topo(p, faces);
    size_t nv = p.size(), ne = topo.edgeVerts.size();
    std::vector<Vec3d> np(nv + ne);
    for (size_t v = 0; v < nv; ++v) {
        int vi = int(v);
        if (topo.Interior(vi)) {
            int n = topo.valence[v];
            double b = Beta(n);
            np[v] = p[v] * (1 - n * b) + topo.neighbourSum[v] * b;
        } else if (topo.Boundary(vi)) {
            np[v] = p[v] * 0.75 + topo.boundarySum[v] * 0.125;
        } else {
            np[v] = p[v];  // corner or non-manifold vertex: kept in place
        }
    }
    for (size_t e = 0; e < ne; ++e) {
        const auto &ev = topo.edgeVerts[e];
        if (topo.edgeFaces[e] == 2) {
            const auto &o = topo.edgeOpposite[e];
            np[nv + e] = (p[ev[0]] + p[ev[1]]) * 0.375 + (p[o[0]] + p[o[1]]) * 0.125;
        } else {
            np[nv + e] = (p[ev[0]] + p[ev[1]]) * 0.5;
        }
    }
    std::vector<Face> nf;
    nf.reserve(faces.size() * 4);
    for (size_t f = 0; f < faces.size(); ++f) {
        int a = faces[f][0], b = faces[f][1], c = faces[f][2];
        int ab = int(nv) + topo.faceEdge[f * 3 + 0], bc = int(nv) + topo.faceEdge[f * 3 + 1],
            ca = int(nv) + topo.faceEdge[f * 3 + 2];
        nf.push_back({a, ab, ca});
        nf.push_back({ab, b, bc});
        nf.push_back({ca, bc, c});
        nf.push_back({ab, bc, ca});
    }
    p = std::move(np);
    faces = std::move(nf);
}

// The one-ring of v in counter-clockwise order (seen from the front), from the faces' (next,
// previous) pairs around v; for a boundary vertex it starts and ends at the boundary
// neighbours. Returns false when the neighbourhood is not a simple fan.
bool OrderedRing(const std::vector<std::pair<int, int>> &pairs, bool boundary,
                 std::vector<int> *ring) {
    ring->clear();
    if (pairs.empty()) return false;
    int start = pairs[0].first;
    if (boundary) {
        start = -1;
        for (const auto &pr : pairs) {
            bool isTo = false;
            for (const auto &q : pairs) isTo |= q.second == pr.first;
            if (!isTo) {
                if (start >= 0) return false;
                start = pr.first;
            }
        }
        if (start < 0) return false;
    }
    int cur = start;
    ring->push_back(cur);
    for (size_t step = 0; step < pairs.size(); ++step) {
        int next = -1;
        for (const auto &pr : pairs)
            if (pr.first == cur) {
                if (next >= 0) return false;
                next = pr.second;
            }
        if (next < 0) return false;
        cur = next;
        if (!boundary && step + 1 == pairs.size()) return cur == start;  // the fan closes
        if (cur == start) return false;                                  // closed too early
        ring->push_back(cur);
    }
    return boundary;
}

// Limit-surface tangents from the control points of the final level (Loop's masks; pbrt-v3's
// boundary masks), crossed into a normal.
Vec3d LimitNormal(const std::vector<Vec3d> &p, int v, const std::vector<int> &ring, bool boundary) {
    int n = int(ring.size());
    Vec3d S(0, 0, 0), T(0, 0, 0);
    if (!boundary) {
        for (int i = 0; i < n; ++i) {
            double a = 2 * Pi * i / n;
            S += p[ring[i]] * std::cos(a);
            T += p[ring[i]] * std::sin(a);
        }
    } else {
        const Vec3d &pv = p[v];
        S = p[ring[n - 1]] - p[ring[0]];
        if (n == 2) {
            T = p[ring[0]] + p[ring[1]] - pv * 2.0;
        } else if (n == 3) {
            T = p[ring[1]] - pv;
        } else if (n == 4) {  // regular boundary vertex
            T = p[ring[0]] * -1.0 + p[ring[1]] * 2.0 + p[ring[2]] * 2.0 + p[ring[3]] * -1.0 +
                pv * -2.0;
        } else {
            double theta = Pi / (n - 1);
            T = (p[ring[0]] + p[ring[n - 1]]) * std::sin(theta);
            for (int i = 1; i < n - 1; ++i)
                T += p[ring[i]] * ((2 * std::cos(theta) - 2) * std::sin(theta * i));
            T = -T;
        }
    }
    return Cross(S, T);
}

}  // namespace

LoopSubdivResult LoopSubdivide(const std::vector<Vec3f> &P, const std::vector<int> &indices,
                               int levels) {
    if (levels < 0 || levels > MaxLoopSubdivLevels)
        throw std::invalid_argument("subdivision levels must be 0 to " +
                                    std::to_string(MaxLoopSubdivLevels));
    if (indices.size() % 3 != 0)
        throw std::invalid_argument("the number of indices must be a multiple of 3");
    LoopSubdivResult result;
    // Referenced vertices only, renumbered; faces with a repeated vertex are dropped.
    std::vector<int> remap(P.size(), -1);
    std::vector<Vec3d> p;
    std::vector<Face> faces;
    for (size_t i = 0; i < indices.size(); i += 3) {
        Face f;
        for (int k = 0; k < 3; ++k) {
            int v = indices[i + k];
            if (v < 0 || size_t(v) >= P.size())
                throw std::invalid_argument("vertex index " + std::to_string(v) +
                                            " out of range (" + std::to_string(P.size()) +
                                            " vertices)");
            f[k] = v;
        }
        if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) {
            result.droppedFaces++;
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            int &r = remap[size_t(f[k])];
            if (r < 0) {
                r = int(p.size());
                p.push_back(Vec3d(P[size_t(f[k])]));
            }
            f[k] = r;
        }
        faces.push_back(f);
    }
    uint64_t outTriangles = uint64_t(faces.size()) << (2 * levels);
    if (outTriangles > MaxLoopSubdivTriangles)
        throw std::invalid_argument(std::to_string(levels) + " levels of subdivision would make " +
                                    std::to_string(outTriangles) + " triangles (limit " +
                                    std::to_string(MaxLoopSubdivTriangles) + ")");
    if (faces.empty()) return result;
    for (int level = 0; level < levels; ++level) Subdivide(p, faces);

    // Limit positions and normals of the final control mesh.
    Topology topo(p, faces);
    size_t nv = p.size();
    std::vector<std::vector<std::pair<int, int>>> around(nv);
    std::vector<Vec3d> faceNormalSum(nv, Vec3d(0, 0, 0));
    for (const Face &f : faces) {
        Vec3d n = Cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);  // area-weighted
        for (int k = 0; k < 3; ++k) {
            around[f[k]].push_back({f[(k + 1) % 3], f[(k + 2) % 3]});
            faceNormalSum[f[k]] += n;
        }
    }
    result.P.resize(nv);
    result.N.resize(nv);
    std::vector<int> ring;
    for (size_t v = 0; v < nv; ++v) {
        int vi = int(v);
        Vec3d lim = p[v];
        if (topo.Interior(vi)) {
            int n = topo.valence[v];
            double g = Gamma(n);
            lim = p[v] * (1 - n * g) + topo.neighbourSum[v] * g;
        } else if (topo.Boundary(vi)) {
            // The boundary is a cubic B-spline, whose limit mask is (1/6, 4/6, 1/6). (pbrt-v3
            // uses (1/5, 3/5, 1/5), which misses the curve; the level-invariance test
            // catches that.)
            lim = p[v] * (4.0 / 6.0) + topo.boundarySum[v] * (1.0 / 6.0);
        }
        Vec3d nrm(0, 0, 0);
        bool boundary = topo.Boundary(vi);
        if ((topo.Interior(vi) || boundary) && OrderedRing(around[v], boundary, &ring))
            nrm = LimitNormal(p, vi, ring, boundary);
        // The masks fix the normal's line; the faces fix its side (and stand in when the
        // neighbourhood is not a simple fan or the tangents degenerate).
        const Vec3d &fn = faceNormalSum[v];
        double len = Length(nrm);
        if (!(len > 1e-12 * std::max(1.0, Length(fn))) || !std::isfinite(len)) nrm = fn;
        if (Dot(nrm, fn) < 0) nrm = -nrm;
        double l2 = Length(nrm);
        result.N[v] = l2 > 0 && std::isfinite(l2) ? Vec3f(nrm / l2) : Vec3f(0, 0, 1);
        result.P[v] = Vec3f(lim);
    }
    result.indices.reserve(faces.size() * 3);
    for (const Face &f : faces) result.indices.insert(result.indices.end(), f.begin(), f.end());
    return result;
}

}  // namespace prism
