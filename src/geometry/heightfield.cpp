#include "geometry/heightfield.h"

#include <cmath>
#include <string>

namespace prism {

PatchMesh TessellateHeightfield(int nu, int nv, const std::vector<double> &Pz) {
    for (auto [name, n] : {std::pair{"nu", nu}, std::pair{"nv", nv}})
        if (n < 2)
            throw PatchParamError(name, std::string("heightfield \"") + name + "\" " +
                                            std::to_string(n) + " must be at least 2");
    uint64_t cells = uint64_t(nu - 1) * uint64_t(nv - 1);
    uint64_t points = uint64_t(nu) * uint64_t(nv);
    if (points > MaxHeightfieldPoints)
        throw PatchParamError("nu", "heightfield of " + std::to_string(nu) + " x " +
                                        std::to_string(nv) + " heights is over the limit of " +
                                        std::to_string(MaxHeightfieldPoints) + " heights");
    if (Pz.size() != points)
        throw PatchParamError("Pz",
                              "heightfield needs \"nu\" * \"nv\" = " + std::to_string(points) +
                                  " heights \"Pz\", got " + std::to_string(Pz.size()));
    PatchMesh m;
    m.P.reserve(points);
    m.uv.reserve(points);
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            double z = Pz[size_t(j) * size_t(nu) + size_t(i)];
            if (!std::isfinite(z))
                throw PatchParamError("Pz", "heightfield height " +
                                                std::to_string(size_t(j) * size_t(nu) + size_t(i)) +
                                                " is not finite");
            float x = float(double(i) / double(nu - 1)), y = float(double(j) / double(nv - 1));
            m.P.push_back(Vec3f(x, y, float(z)));
            m.uv.push_back(Vec2f(x, y));
        }
    m.indices.reserve(6 * cells);
    for (int j = 0; j + 1 < nv; ++j)
        for (int i = 0; i + 1 < nu; ++i) {
            int v00 = j * nu + i, v10 = v00 + 1, v01 = v00 + nu, v11 = v01 + 1;
            m.indices.insert(m.indices.end(), {v00, v10, v11, v00, v11, v01});
        }
    return m;
}

}  // namespace prism
