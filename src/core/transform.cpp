#include "core/transform.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace prism {

Matrix4 Matrix4::Identity() {
    Matrix4 r;
    for (int i = 0; i < 4; ++i) r.m[i][i] = 1;
    return r;
}

Matrix4 Matrix4::operator*(const Matrix4 &o) const {
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += m[i][k] * o.m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

bool Matrix4::IsIdentity() const { return *this == Identity(); }

double Matrix4::Determinant3x3() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Matrix4 Matrix4::Transposed() const {
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = m[j][i];
    return r;
}

// Gauss-Jordan elimination with full pivoting.
bool Matrix4::Inverse(Matrix4 *out) const {
    int indxc[4], indxr[4];
    int ipiv[4] = {0, 0, 0, 0};
    double minv[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) minv[i][j] = m[i][j];
    for (int i = 0; i < 4; i++) {
        int irow = 0, icol = 0;
        double big = 0;
        for (int j = 0; j < 4; j++) {
            if (ipiv[j] != 1) {
                for (int k = 0; k < 4; k++) {
                    if (ipiv[k] == 0) {
                        if (std::abs(minv[j][k]) >= big) {
                            big = std::abs(minv[j][k]);
                            irow = j;
                            icol = k;
                        }
                    } else if (ipiv[k] > 1) {
                        return false;
                    }
                }
            }
        }
        ++ipiv[icol];
        if (irow != icol)
            for (int k = 0; k < 4; ++k) std::swap(minv[irow][k], minv[icol][k]);
        indxr[i] = irow;
        indxc[i] = icol;
        if (minv[icol][icol] == 0 || !std::isfinite(minv[icol][icol])) return false;
        double pivinv = 1 / minv[icol][icol];
        minv[icol][icol] = 1;
        for (int j = 0; j < 4; j++) minv[icol][j] *= pivinv;
        for (int j = 0; j < 4; j++) {
            if (j != icol) {
                double save = minv[j][icol];
                minv[j][icol] = 0;
                for (int k = 0; k < 4; k++) minv[j][k] -= minv[icol][k] * save;
            }
        }
    }
    for (int j = 3; j >= 0; j--) {
        if (indxr[j] != indxc[j]) {
            for (int k = 0; k < 4; k++) std::swap(minv[k][indxr[j]], minv[k][indxc[j]]);
        }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            if (!std::isfinite(minv[i][j])) return false;
            out->m[i][j] = minv[i][j];
        }
    return true;
}

Transform::Transform(const Matrix4 &m) : m_(m) {
    if (!m.Inverse(&mInv_)) throw std::invalid_argument("singular transformation matrix");
}

Vec3d Transform::Point(const Vec3d &p) const {
    const auto &m = m_.m;
    double x = m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3];
    double y = m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3];
    double z = m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3];
    double w = m[3][0] * p.x + m[3][1] * p.y + m[3][2] * p.z + m[3][3];
    if (w == 1) return {x, y, z};
    return Vec3d(x, y, z) / w;
}

Vec3d Transform::Vector(const Vec3d &v) const {
    const auto &m = m_.m;
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Vec3d Transform::Normal(const Vec3d &n) const {
    const auto &mi = mInv_.m;
    return {mi[0][0] * n.x + mi[1][0] * n.y + mi[2][0] * n.z,
            mi[0][1] * n.x + mi[1][1] * n.y + mi[2][1] * n.z,
            mi[0][2] * n.x + mi[1][2] * n.y + mi[2][2] * n.z};
}

Bounds3d Transform::Bounds(const Bounds3d &b) const {
    Bounds3d r;
    for (int i = 0; i < 8; ++i) r.Expand(Point(b.Corner(i)));
    return r;
}

Vec3d Transform::PointError(const Vec3d &p, const Vec3d &pErr, double eps) const {
    // gamma3 * (|M| |p| + |t|) for the rounding of this transform, plus the propagated input
    // error (gamma3 + 1) |M| pErr (pbrt-v3 Transform::operator()(p, pError, ...)).
    const auto &m = m_.m;
    double g3 = 3 * eps / (1 - 3 * eps);
    Vec3d r;
    for (int i = 0; i < 3; ++i) {
        double a = std::abs(m[i][0] * p.x) + std::abs(m[i][1] * p.y) + std::abs(m[i][2] * p.z) +
                   std::abs(m[i][3]);
        double e =
            std::abs(m[i][0]) * pErr.x + std::abs(m[i][1]) * pErr.y + std::abs(m[i][2]) * pErr.z;
        r[i] = g3 * a + (g3 + 1) * e;
    }
    return r;
}

std::string Transform::ToString() const {
    std::ostringstream s;
    s << "[";
    for (int i = 0; i < 4; ++i) {
        s << (i ? " [" : "[");
        for (int j = 0; j < 4; ++j) s << m_.m[i][j] << (j < 3 ? " " : "]");
    }
    s << "]";
    return s.str();
}

Transform Translate(const Vec3d &d) {
    Matrix4 m = Matrix4::Identity(), mi = Matrix4::Identity();
    m.m[0][3] = d.x;
    m.m[1][3] = d.y;
    m.m[2][3] = d.z;
    mi.m[0][3] = -d.x;
    mi.m[1][3] = -d.y;
    mi.m[2][3] = -d.z;
    return {m, mi};
}

Transform Scale(double x, double y, double z) {
    Matrix4 m = Matrix4::Identity();
    m.m[0][0] = x;
    m.m[1][1] = y;
    m.m[2][2] = z;
    return Transform(m);
}

Transform Rotate(double deg, const Vec3d &axis) {
    Vec3d a = Normalize(axis);
    double s = std::sin(Radians(deg)), c = std::cos(Radians(deg));
    Matrix4 m = Matrix4::Identity();
    m.m[0][0] = a.x * a.x + (1 - a.x * a.x) * c;
    m.m[0][1] = a.x * a.y * (1 - c) - a.z * s;
    m.m[0][2] = a.x * a.z * (1 - c) + a.y * s;
    m.m[1][0] = a.x * a.y * (1 - c) + a.z * s;
    m.m[1][1] = a.y * a.y + (1 - a.y * a.y) * c;
    m.m[1][2] = a.y * a.z * (1 - c) - a.x * s;
    m.m[2][0] = a.x * a.z * (1 - c) - a.y * s;
    m.m[2][1] = a.y * a.z * (1 - c) + a.x * s;
    m.m[2][2] = a.z * a.z + (1 - a.z * a.z) * c;
    return {m, m.Transposed()};
}
Transform RotateX(double deg) { return Rotate(deg, {1, 0, 0}); }
Transform RotateY(double deg) { return Rotate(deg, {0, 1, 0}); }
Transform RotateZ(double deg) { return Rotate(deg, {0, 0, 1}); }

Transform LookAt(const Vec3d &eye, const Vec3d &look, const Vec3d &up) {
    Vec3d d = look - eye;
    if (LengthSquared(d) == 0)
        throw std::invalid_argument("LookAt: eye and look point are the same");
    Vec3d dir = Normalize(d);
    Vec3d upn = LengthSquared(up) > 0 ? Normalize(up) : up;
    Vec3d right = Cross(upn, dir);
    if (LengthSquared(right) == 0)
        throw std::invalid_argument("LookAt: up vector and viewing direction are parallel");
    right = Normalize(right);
    Vec3d newUp = Cross(dir, right);
    Matrix4 camToWorld = Matrix4::Identity();
    for (int i = 0; i < 3; ++i) {
        camToWorld.m[i][0] = right[i];
        camToWorld.m[i][1] = newUp[i];
        camToWorld.m[i][2] = dir[i];
        camToWorld.m[i][3] = eye[i];
    }
    Matrix4 worldToCam;
    if (!camToWorld.Inverse(&worldToCam)) throw std::invalid_argument("LookAt: singular");
    return {worldToCam, camToWorld};
}

Transform FromPbrtMatrix(const double v[16]) {
    Matrix4 m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m.m[r][c] = v[c * 4 + r];
    return Transform(m);
}

}  // namespace prism
