// The pixel filter a scene names (PixelFilter), or its pbrt version's default
// (assembly/camera_film.h).
#include <cmath>
#include <string>

#include "assembly/camera_film.h"

namespace prism {

// PixelFilter "box", "gaussian", "triangle", "mitchell", "sinc" (pbrt-v3's and pbrt-v4's; without a
// PixelFilter line pbrt-v3 filters with the box, pbrt-v4 with the gaussian). Parameters:
//   xwidth, ywidth    float  0.5 (box), 2, 4 (sinc)  pbrt-v3: the filter's radius, in (0, 16]
//                                          pixels
//   xradius, yradius  float  0.5 (box), 1.5 (gaussian), 2, 4 (sinc)  pbrt-v4's name for the
//                                          radius
//   alpha             float  2             gaussian: its falloff exp(-alpha x²) (pbrt-v3)
//   sigma             float  0.5           gaussian: its standard deviation (pbrt-v4; alpha
//                                          is 1 / (2 sigma²))
//   B, C              float  1/3, 1/3      mitchell: its two parameters
//   tau               float  3             sinc: sinc(x) sinc(x / tau), a Lanczos window
void BuildPixelFilter(BuildContext &ctx) {
    const SceneDescription &desc = ctx.desc;
    RenderScene &scene = ctx.scene;
    Diagnostics &diag = ctx.diag;
    const ParamSet &fp = desc.filter.params;
    const bool v4 = desc.pbrtVersion.version == 4;
    Filter f;
    // pbrt-v4's default filter is its gaussian (radius 1.5, sigma 0.5), pbrt-v3's the box.
    std::string ft = v4 && !desc.filter.loc.Valid() ? "gaussian" : desc.filter.type;
    bool known =
        ft == "box" || ft == "gaussian" || ft == "triangle" || ft == "mitchell" || ft == "sinc";
    if (known) {
        // Radii: 0.5 for the box, 4 for the sinc, 2 for the others, but 1.5 for pbrt-v4's
        // gaussian.
        const float defaultRadius = ft == "box"              ? 0.5f
                                    : ft == "sinc"           ? 4.f
                                    : v4 && ft == "gaussian" ? 1.5f
                                                             : 2.f;
        f.radiusX = fp.GetFloat("xradius", fp.GetFloat("xwidth", defaultRadius));
        f.radiusY = fp.GetFloat("yradius", fp.GetFloat("ywidth", defaultRadius));
    }
    if (ft == "box") {
        f.kind = Filter::Kind::Box;
    } else if (ft == "gaussian") {
        f.kind = Filter::Kind::Gaussian;
        // pbrt-v4's max(0, G(x, sigma) - G(radius, sigma)) is pbrt-v3's shape with alpha =
        // 1 / (2 sigma²) (its default sigma 0.5 is pbrt-v3's default alpha 2); the
        // normalisation cancels in the weighted average.
        f.alpha = fp.GetFloat("alpha", 2.f);
        if (const Param *sp = fp.Find("sigma")) {
            const float sigma = fp.GetFloat("sigma", 0.5f);
            if (!(sigma > 0 && std::isfinite(sigma)))
                throw SceneError(sp->loc, "pixel filter sigma must be positive");
            f.alpha = 1 / (2 * sigma * sigma);
        }
    } else if (ft == "triangle") {
        f.kind = Filter::Kind::Triangle;
    } else if (ft == "mitchell") {
        f.kind = Filter::Kind::Mitchell;
        f.B = fp.GetFloat("B", 1.f / 3);
        f.C = fp.GetFloat("C", 1.f / 3);
    } else if (ft == "sinc") {
        f.kind = Filter::Kind::LanczosSinc;
        f.tau = fp.GetFloat("tau", 3.f);
        if (!(f.tau > 0 && std::isfinite(f.tau)))
            throw SceneError(fp.Find("tau")->loc, "pixel filter tau must be positive");
    } else {
        diag.Warn(desc.filter.loc,
                  "pixel filter " + Quote(ft) + " is not supported; using gaussian");
        f.kind = Filter::Kind::Gaussian;
        f.radiusX = f.radiusY = 2;
        fp.MarkAllUsed();
    }
    if (!(f.radiusX > 0 && f.radiusY > 0 && f.radiusX <= 16 && f.radiusY <= 16))
        throw SceneError(desc.filter.loc, "pixel filter width must be in (0, 16]");
    scene.filter = f;
    fp.ReportUnused(diag, "pixel filter");
}

}  // namespace prism
