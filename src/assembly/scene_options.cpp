#include "assembly/scene_options.h"

#include <limits>

namespace prism {

namespace {

// pbrt-v4's options (its Option directive and command line) that do not change what Prism
// renders, and why.
struct Unsimulated {
    const char *name;
    const char *why;
};
constexpr Unsimulated UnsimulatedOptions[] = {
    {"disablewavelengthjitter", "Prism renders RGB, not sampled wavelengths"},
    {"forcediffuse", "not supported: materials keep their own BSDFs"},
    {"displacementedgescale", "Prism does not displace meshes"},
    {"rendercoordsys", "Prism renders in its own camera-relative space"},
    {"pixelstats", "per-pixel statistics images are not written (see --stats)"},
    {"wavefront", "Prism has one CPU renderer"},
    {"gpu", "Prism has one CPU renderer"},
    {"quiet", "use --quiet"},
    {"nthreads", "use --threads"},
    {"msereferenceimage", "use prism bench compare --reference"},
    {"msereferenceout", "use prism bench compare --reference"},
    {"disableimagetextures", "not supported: image textures are read"},
    {"usegpu", "Prism has one CPU renderer"},
};

}  // namespace

// Option "(every option)" (pbrt-v4's). Parameters:
//   seed                     integer  0      the seed of every sampler (a Sampler's own
//                                            "seed" wins)
//   disablepixeljitter       bool     false  every camera sample at its pixel's centre
//   disabletexturefiltering  bool     false  image textures looked up at a point, unfiltered
//                                            (as --texture-filter point)
SceneOptions ReadSceneOptions(const SceneDescription &desc, Diagnostics &diag) {
    const ParamSet &ps = desc.options;
    SceneOptions o;
    if (const Param *p = ps.Find("seed")) {
        const int seed = ps.GetInt("seed", 0);
        if (seed < 0) throw SceneError(p->loc, "Option \"seed\" must not be negative");
        o.seed = uint32_t(seed);
    }
    o.disablePixelJitter = ps.GetBool("disablepixeljitter", false);
    o.disableTextureFiltering = ps.GetBool("disabletexturefiltering", false);
    for (const Param &p : ps.Params()) {
        if (p.lookedUp) continue;
        p.lookedUp = true;
        const char *why = nullptr;
        for (const Unsimulated &u : UnsimulatedOptions)
            if (p.name == u.name) why = u.why;
        diag.Warn(p.loc, "Option " + Quote(p.name) +
                             (why ? std::string(" has no effect: ") + why
                                  : std::string(" is not a pbrt-v4 option Prism knows; ignored")));
    }
    return o;
}

}  // namespace prism
