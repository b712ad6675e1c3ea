#include "assembly/lens_file.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace prism {

namespace {

// Bounds on a lens file's values, in millimetres: far beyond any real lens, small enough that
// the camera's arithmetic stays finite.
constexpr double MaxLensLength = 1e5;
constexpr double MaxLensEta = 10;

}  // namespace

std::vector<LensInterface> ParseLensFile(const std::string &text, const std::string &file) {
    std::vector<LensInterface> out;
    size_t pos = 0;
    int line = 0;
    while (pos < text.size()) {
        ++line;
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        std::string row = text.substr(pos, end - pos);
        pos = end + 1;
        if (const size_t hash = row.find('#'); hash != std::string::npos) row.resize(hash);
        double v[4];
        int n = 0;
        size_t i = 0;
        auto at = [&](size_t col) { return FileLoc{file, line, int(col) + 1}; };
        while (true) {
            while (i < row.size() && std::isspace((unsigned char)row[i])) ++i;
            if (i >= row.size()) break;
            const char *begin = row.c_str() + i;
            char *stop = nullptr;
            errno = 0;
            const double x = std::strtod(begin, &stop);
            const size_t len = size_t(stop - begin);
            if (len == 0 || (stop && *stop && !std::isspace((unsigned char)*stop)))
                throw SceneError(at(i), "lens file: expected a number");
            if (errno == ERANGE || !std::isfinite(x) || std::abs(x) > MaxLensLength)
                throw SceneError(at(i), "lens file: value out of range (at most 1e5 mm)");
            if (n == 4)
                throw SceneError(at(i),
                                 "lens file: more than four numbers on a line (radius, "
                                 "thickness, eta, aperture diameter)");
            v[n++] = x;
            i += len;
        }
        if (n == 0) continue;
        if (n != 4)
            throw SceneError(at(row.size()),
                             "lens file: expected four numbers (radius, "
                             "thickness, eta, aperture diameter), got " +
                                 std::to_string(n));
        if (v[1] < 0) throw SceneError(at(0), "lens file: negative thickness");
        if (v[2] != 0 && !(v[2] >= 1 && v[2] <= MaxLensEta))
            throw SceneError(at(0), "lens file: index of refraction must be 0 (air) or 1 to 10");
        if (!(v[3] > 0)) throw SceneError(at(0), "lens file: aperture diameter must be positive");
        if (v[0] != 0 && std::abs(v[0]) < v[3] / 2)
            throw SceneError(at(0), "lens file: radius of curvature smaller than the aperture");
        if (int(out.size()) == MaxLensInterfaces)
            throw SceneError(
                at(0), "lens file: more than " + std::to_string(MaxLensInterfaces) + " interfaces");
        out.push_back({v[0] * 1e-3, v[1] * 1e-3, v[2], v[3] * 0.5e-3});
    }
    if (out.empty()) throw SceneError(FileLoc{file, 0, 0}, "lens file lists no interfaces");
    return out;
}

}  // namespace prism
