#include "tools/bench/knot.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "core/output_file.h"

namespace prism {

namespace {

using V3 = std::array<double, 3>;

// The constants of gen_knot.py.
constexpr int PKnot = 2, QKnot = 3;          // torus-knot winding numbers
constexpr double KR = 1.6, Kr = 0.6;         // knot curve: torus radii
constexpr double Tube = 0.32, Ridge = 0.12;  // tube radius, relative displacement amplitude
constexpr V3 Center{0.0, 2.75, 0.0};
constexpr double Ground = 30.0;  // ground quad half size, y = 0
constexpr int Width = 800, Height = 600;
constexpr V3 Eye{0.0, 3.5, -9.0}, Look{0.0, 2.2, 0.0};
constexpr double VFov = 40.0;
constexpr V3 LightPos{-4.0, 10.0, -6.0}, LightI{400.0, 400.0, 400.0};
constexpr V3 KnotKd{0.80, 0.35, 0.08}, GroundKd{0.60, 0.60, 0.60};
constexpr double PovFadeD = 0.1;
constexpr double Pi = 3.14159265358979323846;

// The same operations in the same order as the Python helpers, so the doubles agree bit for bit.
V3 Sub(const V3 &a, const V3 &b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 Add(const V3 &a, const V3 &b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
V3 Mul(const V3 &a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double Dot(const V3 &a, const V3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 Cross(const V3 &a, const V3 &b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V3 Norm(const V3 &a) {
    double l = std::sqrt(Dot(a, a));
    return l > 0 ? V3{a[0] / l, a[1] / l, a[2] / l} : V3{0.0, 1.0, 0.0};
}
V3 Curve(double t) {
    double rr = KR + Kr * std::cos(QKnot * t);
    return {rr * std::cos(PKnot * t), rr * std::sin(PKnot * t), Kr * std::sin(QKnot * t)};
}
V3 RotateAbout(const V3 &v, const V3 &axis, double ang) {
    double c = std::cos(ang), s = std::sin(ang);
    return Add(Add(Mul(v, c), Mul(Cross(axis, v), s)), Mul(axis, Dot(axis, v) * (1 - c)));
}

// Python's f(): "%.6f" without trailing zeros (and dot); "0" for tiny values.
std::string F(double x) {
    if (!(std::abs(x) > 1e-12)) return "0";
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.6f", x);
    std::string s = buf;
    while (!s.empty() && s.back() == '0') s.pop_back();
    while (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}
std::string PovV3(const V3 &v) { return "<" + F(v[0]) + ", " + F(v[1]) + ", " + F(v[2]) + ">"; }
std::string L3(const V3 &v) { return F(v[0]) + " " + F(v[1]) + " " + F(v[2]); }
std::string Printf(const char *fmt, double a, double b, double c) {
    char buf[128];
    std::snprintf(buf, sizeof(buf), fmt, a, b, c);
    return buf;
}

// Through AtomicOutputFile (core/output_file.h), as every output: a new temporary file beside
// `path` (never through a symbolic link), renamed over it once complete.
void WriteFile(const std::string &path, const std::string &data) {
    WriteFileAtomically(path, data);
}

double HFov() {
    // Python's math.radians/degrees multiply by pi/180 and 180/pi.
    return 2 * (std::atan(std::tan(VFov / 2 * (Pi / 180)) * Width / Height) * (180 / Pi));
}

const std::array<V3, 4> &GroundVerts() {
    static const std::array<V3, 4> gv{V3{-Ground, 0.0, -Ground}, V3{Ground, 0.0, -Ground},
                                      V3{Ground, 0.0, Ground}, V3{-Ground, 0.0, Ground}};
    return gv;
}

// The pbrt header up to and including the light (shared with the empty scene).
std::string PbrtHeader(const char *comment) {
    std::string s = comment;
    s += "LookAt " + L3(Eye) + "  " + L3(Look) + "  0 1 0\n";
    s += "Camera \"perspective\" \"float fov\" [ " + F(VFov) + " ]\n";
    s += "Sampler \"stratified\" \"integer xsamples\" [ 1 ] \"integer ysamples\" [ 1 ] "
         "\"bool jitter\" \"false\"\n";
    s += "PixelFilter \"box\" \"float xwidth\" [ 0.5 ] \"float ywidth\" [ 0.5 ]\n";
    s += "Film \"image\" \"integer xresolution\" [ " + std::to_string(Width) +
         " ] \"integer yresolution\" [ " + std::to_string(Height) +
         " ] \"string filename\" \"knot.exr\"\n";
    s += "Integrator \"whitted\" \"integer maxdepth\" [ 5 ]\nWorldBegin\n";
    s += "LightSource \"point\" \"point3 from\" [ " + L3(LightPos) + " ] \"rgb I\" [ " +
         L3(LightI) + " ]\n";
    return s;
}

std::string PlyFile(const KnotMesh &m) {
    char header[512];
    std::snprintf(header, sizeof(header),
                  "ply\nformat binary_little_endian 1.0\ncomment gen_knot.py torus knot\n"
                  "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
                  "property float nx\nproperty float ny\nproperty float nz\n"
                  "element face %zu\nproperty list uchar int vertex_indices\nend_header\n",
                  m.p.size(), m.faces.size());
    std::string s = header;
    size_t h = s.size();
    s.resize(h + m.p.size() * 24 + m.faces.size() * 13);
    char *out = s.data() + h;
    for (size_t i = 0; i < m.p.size(); ++i) {
        float v[6] = {float(m.p[i][0]), float(m.p[i][1]), float(m.p[i][2]),
                      float(m.n[i][0]), float(m.n[i][1]), float(m.n[i][2])};
        std::memcpy(out, v, 24);  // x86-64 is little-endian, as the header says
        out += 24;
    }
    for (const auto &f : m.faces) {
        *out++ = 3;
        int32_t idx[3] = {f[0], f[1], f[2]};
        std::memcpy(out, idx, 12);
        out += 12;
    }
    return s;
}

std::string PovInclude(const KnotMesh &m) {
    std::string s =
        "// generated by gen_knot.py\n#declare Knot_Mesh = mesh2 {\n vertex_vectors { " +
        std::to_string(m.p.size()) + ",\n";
    for (size_t i = 0; i < m.p.size(); ++i)
        s += (i ? ",\n" : "") + Printf("<%.6f,%.6f,%.6f>", m.p[i][0], m.p[i][1], m.p[i][2]);
    s += "\n }\n normal_vectors { " + std::to_string(m.n.size()) + ",\n";
    for (size_t i = 0; i < m.n.size(); ++i)
        s += (i ? ",\n" : "") + Printf("<%.6f,%.6f,%.6f>", m.n[i][0], m.n[i][1], m.n[i][2]);
    s += "\n }\n face_indices { " + std::to_string(m.faces.size()) + ",\n";
    for (size_t i = 0; i < m.faces.size(); ++i) {
        const auto &f = m.faces[i];
        s += (i ? ",\n<" : "<") + std::to_string(f[0]) + "," + std::to_string(f[1]) + "," +
             std::to_string(f[2]) + ">";
    }
    s += "\n }\n}\n";
    const auto &gv = GroundVerts();
    s += "#declare Ground_Mesh = mesh2 {\n vertex_vectors { 4, " + PovV3(gv[0]) + ", " +
         PovV3(gv[1]) + ", " + PovV3(gv[2]) + ", " + PovV3(gv[3]) +
         " }\n face_indices { 2, <0,2,1>, <0,3,2> }\n}\n";
    return s;
}

std::string PovScene(size_t ntri) {
    double scale = 1.0 / (2 * PovFadeD * PovFadeD) / Pi;
    char angle[96];
    std::snprintf(angle, sizeof(angle), "angle %.6f  // = %.1f deg vertical", HFov(), VFov);
    std::string finish = " finish { ambient 0 emission 0 diffuse 1 specular 0 phong 0 } } }\n";
    return "// Triangle-heavy scene: " + std::to_string(ntri) +
           " triangles in two mesh2 objects. Generated by gen_knot.py.\n"
           "// povray +Iknot.pov +Oknot.png +W800 +H600 -D +FN -A +WT2\n"
           "#version 3.7;\n"
           "#ifndef (TL) #declare TL = 5; #end\n"
           "global_settings { assumed_gamma 1.0 max_trace_level TL ambient_light rgb 0 }\n"
           "background { rgb 0 }\n"
           "camera { perspective location " +
           PovV3(Eye) + " right x*image_width/image_height up y sky y\n         " + angle +
           "\n         look_at " + PovV3(Look) +
           " }\n"
           "light_source { " +
           PovV3(LightPos) + " color rgb " + PovV3(Mul(LightI, scale)) + " fade_distance " +
           F(PovFadeD) + " fade_power 2 }  // pbrt point I = " + L3(LightI) +
           "\n#include \"knot_mesh.inc\"\n"
           "object { Knot_Mesh   texture { pigment { rgb " +
           PovV3(KnotKd) + " }" + finish + "object { Ground_Mesh texture { pigment { rgb " +
           PovV3(GroundKd) + " }" + finish;
}

}  // namespace

KnotMesh BuildKnot(int nu, int nv) {
    if (nu < 3 || nv < 3) throw std::runtime_error("knot: nu and nv must be at least 3");
    KnotMesh m;
    std::vector<double> ts(size_t(nu), 0.0);
    std::vector<V3> C(static_cast<size_t>(nu)), T(static_cast<size_t>(nu));
    for (int i = 0; i < nu; ++i) {
        ts[size_t(i)] = 2 * Pi * i / nu;
        C[size_t(i)] = Curve(ts[size_t(i)]);
    }
    for (int i = 0; i < nu; ++i)
        T[size_t(i)] = Norm(Sub(C[size_t((i + 1) % nu)], C[size_t((i - 1 + nu) % nu)]));
    // Parallel-transport frame, then spread the closing twist evenly.
    V3 n0 = Norm(Cross(T[0], V3{0.0, 0.0, 1.0}));
    std::vector<V3> Nf{n0};
    for (int i = 1; i <= nu; ++i) {
        const V3 &t = T[size_t(i % nu)];
        V3 n = Nf.back();
        Nf.push_back(Norm(Sub(n, Mul(t, Dot(n, t)))));
    }
    V3 end = Nf[size_t(nu)];
    double ang = std::atan2(Dot(Cross(end, n0), T[0]), Dot(end, n0));
    for (int i = 0; i < nu; ++i)
        Nf[size_t(i)] = RotateAbout(Nf[size_t(i)], T[size_t(i)], ang * i / nu);
    m.p.reserve(size_t(nu) * size_t(nv));
    for (int i = 0; i < nu; ++i) {
        const V3 &t = T[size_t(i)], &n = Nf[size_t(i)];
        V3 b = Cross(t, n);
        for (int j = 0; j < nv; ++j) {
            double v = 2 * Pi * j / nv;
            double rad = Tube * (1 + Ridge * std::sin(7 * v + 60 * ts[size_t(i)]));
            V3 d = Add(Mul(n, std::cos(v)), Mul(b, std::sin(v)));
            V3 p = Add(C[size_t(i)], Mul(d, rad));
            m.p.push_back({p[0] + Center[0], p[1] + Center[1], p[2] + Center[2]});
        }
    }
    m.faces.reserve(size_t(nu) * size_t(nv) * 2);
    for (int i = 0; i < nu; ++i) {
        int i1 = (i + 1) % nu;
        for (int j = 0; j < nv; ++j) {
            int j1 = (j + 1) % nv;
            int a = i * nv + j, b = i1 * nv + j, c = i1 * nv + j1, d = i * nv + j1;
            m.faces.push_back({a, b, c});
            m.faces.push_back({a, c, d});
        }
    }
    // Area-weighted vertex normals.
    std::vector<V3> acc(m.p.size(), V3{0.0, 0.0, 0.0});
    for (const auto &f : m.faces) {
        const V3 &pa = m.p[size_t(f[0])], &pb = m.p[size_t(f[1])], &pc = m.p[size_t(f[2])];
        V3 fn = Cross(Sub(pb, pa), Sub(pc, pa));
        for (int k : f) {
            V3 &q = acc[size_t(k)];
            q[0] += fn[0];
            q[1] += fn[1];
            q[2] += fn[2];
        }
    }
    m.n.reserve(acc.size());
    for (const V3 &q : acc) m.n.push_back(Norm(q));
    // Make normals point outwards (away from the curve).
    if (Dot(m.n[0], Sub(m.p[0], Add(C[0], Center))) < 0) {
        for (V3 &n : m.n) n = Mul(n, -1.0);
        for (auto &f : m.faces) std::swap(f[1], f[2]);
    }
    return m;
}

KnotFiles WriteKnotScene(const std::string &dir, int nu, int nv, bool pov) {
    std::filesystem::create_directories(dir);
    KnotMesh m = BuildKnot(nu, nv);
    KnotFiles kf;
    kf.vertices = m.p.size();
    kf.triangles = m.faces.size() + 2;
    std::filesystem::path d(dir);
    kf.ply = (d / "knot.ply").string();
    WriteFile(kf.ply, PlyFile(m));
    const auto &gv = GroundVerts();
    std::string s =
        PbrtHeader("# Triangle-heavy scene (matches knot.pov). Generated by gen_knot.py.\n");
    s += "AttributeBegin\n  Material \"matte\" \"rgb Kd\" [ " + L3(KnotKd) +
         " ]\n"
         "  Shape \"plymesh\" \"string filename\" \"knot.ply\"\nAttributeEnd\n";
    s += "AttributeBegin\n  Material \"matte\" \"rgb Kd\" [ " + L3(GroundKd) +
         " ]\n"
         "  Shape \"trianglemesh\" \"integer indices\" [ 0 2 1  0 3 2 ] \"point3 P\" [ " +
         L3(gv[0]) + "  " + L3(gv[1]) + "  " + L3(gv[2]) + "  " + L3(gv[3]) +
         " ]\n"
         "AttributeEnd\nWorldEnd\n";
    kf.pbrt = (d / "knot.pbrt").string();
    WriteFile(kf.pbrt, s);
    if (pov) {
        kf.povInclude = (d / "knot_mesh.inc").string();
        WriteFile(kf.povInclude, PovInclude(m));
        kf.pov = (d / "knot.pov").string();
        WriteFile(kf.pov, PovScene(kf.triangles));
    }
    return kf;
}

std::string WriteEmptyScene(const std::string &dir) {
    std::filesystem::create_directories(dir);
    std::string path = (std::filesystem::path(dir) / "empty.pbrt").string();
    WriteFile(path, PbrtHeader("# The knot scene's camera and light with no shapes "
                               "(prism bench suite's memory baseline).\n") +
                        "WorldEnd\n");
    return path;
}

}  // namespace prism
