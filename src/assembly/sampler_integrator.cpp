// Sampler and Integrator directives → the RenderScene's sample pattern, samples per pixel,
// integrator and maximum depth (assembly/camera_film.h).
#include <algorithm>

#include "assembly/camera_film.h"
#include "assembly/directive_params.h"
#include "core/pbrt_defaults.h"
#include "render/renderer.h"

namespace prism {
namespace {

// How Prism draws each pbrt sampler's samples (render/sampler.h SamplePattern). A name that is
// not its own pattern is drawn as another (SamplerSubstitute), with a warning saying why.
struct SamplerRule {
    const char *name;
    SamplePattern pattern;
    const char *substitute;  // null: drawn as itself
    const char *reason;
};
constexpr SamplerRule SamplerRules[] = {
    {"stratified", SamplePattern::Stratified, nullptr, nullptr},
    {"random", SamplePattern::Independent, nullptr, nullptr},
    {"independent", SamplePattern::Independent, nullptr, nullptr},
    {"02sequence", SamplePattern::ZeroTwo, nullptr, nullptr},
    {"lowdiscrepancy", SamplePattern::ZeroTwo, nullptr, nullptr},
    {"paddedsobol", SamplePattern::PaddedSobol, nullptr, nullptr},
    {"zsobol", SamplePattern::ZSobol, nullptr, nullptr},
    {"sobol", SamplePattern::Sobol, nullptr, nullptr},
    {"halton", SamplePattern::Halton, nullptr, nullptr},
    {"pmj02bn", SamplePattern::PaddedSobol, "paddedsobol",
     "pmj02bn's points are per-pixel (0,2)-sequences like paddedsobol's, without the "
     "blue-noise selection"},
    {"maxmindist", SamplePattern::Stratified, "stratified",
     "Prism has no max-min-distance sequence"},
};

const SamplerRule *FindSamplerRule(const std::string &name) {
    for (const SamplerRule &r : SamplerRules)
        if (name == r.name) return &r;
    return nullptr;
}

}  // namespace

std::vector<std::string> SamplerNames() {
    std::vector<std::string> names;
    for (const SamplerRule &r : SamplerRules) names.push_back(r.name);
    return names;
}

namespace {

std::string SamplerSubstitute(const std::string &name) {
    const SamplerRule *r = FindSamplerRule(name);
    if (!r) return "stratified";
    return r->substitute ? r->substitute : "";
}

std::string SamplerSubstituteReason(const std::string &name) {
    const SamplerRule *r = FindSamplerRule(name);
    return r ? r->reason : "Prism does not know this sampler";
}

SamplePattern PatternOfSampler(const std::string &name) {
    const SamplerRule *r = FindSamplerRule(name);
    return r ? r->pattern : SamplePattern::Stratified;
}

}  // namespace

// Sampler "stratified", "random", "02sequence", "lowdiscrepancy", "halton", "sobol",
//   "zsobol", "paddedsobol", "pmj02bn", "independent", "maxmindist" (pbrt-v3's and pbrt-v4's;
// how each is drawn: SamplerRules above, docs/USAGE.md "Samplers"). Parameters:
//   xsamples, ysamples  integer  4, 4  stratified: the samples per pixel are their product
//   jitter              bool     true  stratified: read, no effect
//   pixelsamples        integer  16    the others (random: 4; sobol: rounded up to a power of
//                                      two, with a warning, as pbrt does); --spp wins
//   randomization       string   "fastowen"  zsobol, paddedsobol, sobol: "fastowen" and
//                                "owen" (a nested uniform scramble), "permutedigits" (XOR),
//                                "none" (sobol's default in a pbrt-v3 file, whose sampler does
//                                not randomise); halton: "permutedigits" (its default: random
//                                digit permutations), "owen", "none"
//   seed                integer  0     zsobol, paddedsobol, sobol, halton: another randomisation
int SceneSamplesPerPixel(const SceneDescription &desc) {
    const ParamSet &sp = desc.sampler.params;
    if (desc.sampler.type == "stratified") {
        // In 64 bits: the product of two file values must not overflow.
        int64_t n = int64_t(sp.GetInt("xsamples", 4)) * sp.GetInt("ysamples", 4);
        return int(std::clamp<int64_t>(n, -(int64_t(1) << 30), int64_t(1) << 30));
    }
    return sp.GetInt("pixelsamples", desc.sampler.type == "random" ? 4 : 16);
}

void BuildSampler(BuildContext &ctx) {
    const SceneDescription &desc = ctx.desc;
    const BuildSettings &settings = ctx.settings;
    RenderScene &scene = ctx.scene;
    Diagnostics &diag = ctx.diag;
    const ParamSet &sp = desc.sampler.params;
    int spp = SceneSamplesPerPixel(desc);
    if (desc.sampler.type == "stratified") sp.MarkUsed("jitter");
    // The integrators that draw PixelSamples draw each sampler's samples as SamplerRules says;
    // the others, and a sampler Prism does not have, draw Prism's stratified (correlated
    // multi-jittered) samples, with a warning. The default (no Sampler directive) is not named.
    // --sampler replaces the type (and its parameters but the count).
    const bool replaced = !settings.sampler.empty();
    const std::string &st = replaced ? settings.sampler : desc.sampler.type;
    const FileLoc loc = replaced ? FileLoc{} : desc.sampler.loc;
    if (replaced) sp.MarkAllUsed();
    const std::string context = "sampler " + Quote(st);
    // render/integrator.h IntegratorTraits: whitted, distribution, bdpt, mlt and sppm do not.
    const bool patterns = scene.integrator->Traits().samplePatterns;
    SamplerSettings &ss = scene.sampler;
    ss.seed = ctx.options.seed;  // Option "seed"; a Sobol sampler's own "seed" wins
    ss.centres = ctx.options.disablePixelJitter;
    const std::string substitute = SamplerSubstitute(st);
    const std::string drawn = substitute.empty() ? st : substitute;
    if (patterns) ss.pattern = PatternOfSampler(drawn);
    if (!substitute.empty() && (replaced || loc.Valid()))
        diag.Warn(loc,
                  context +
                      (substitute == "stratified" ? " is replaced by Prism's stratified sampler"
                                                  : " is drawn as " + Quote(substitute)) +
                      ": " + SamplerSubstituteReason(st));
    else if (!patterns && st != "stratified" && (replaced || loc.Valid()))
        diag.Warn(loc, context +
                           " is replaced by Prism's stratified sampler: "
                           "the integrator " +
                           Quote(scene.integrator->Name()) + " draws its own");
    // The Sobol and Halton samplers' "randomization" (def under --sampler) and "seed".
    auto randomization = [&](const char *def) {
        return replaced ? std::string(def) : sp.GetString("randomization", def);
    };
    auto badRandomization = [&](const std::string &r, const std::string &expected) {
        const Param *p = sp.Find("randomization");
        return SceneError(p ? p->loc : desc.sampler.loc,
                          context + ": randomization " + Quote(r) + " is not one of " + expected);
    };
    if (DrawsCameraDims(ss.pattern) && !replaced && sp.Find("seed"))
        ss.seed = uint32_t(sp.GetInt("seed", 0));
    if (IsSobolPattern(ss.pattern) || ss.pattern == SamplePattern::Sobol) {
        // pbrt-v3's SobolSampler draws the bare sequence; pbrt-v4's scrambles it.
        const bool bare = ss.pattern == SamplePattern::Sobol && desc.pbrtVersion.version != 4;
        const std::string r = randomization(bare ? "none" : "fastowen");
        if (r == "fastowen" || r == "owen")
            ss.scramble = SobolScramble::Owen;
        else if (r == "permutedigits")
            ss.scramble = SobolScramble::Xor;
        else if (r == "none")
            ss.scramble = SobolScramble::None;
        else
            throw badRandomization(r, "fastowen, owen, permutedigits, none");
        const int res = std::max(scene.resolution.x, scene.resolution.y);
        ss.log2Res = uint8_t(CeilLog2(uint64_t(std::max(res, 1))));
        if (ss.pattern == SamplePattern::Sobol)
            ss.sobol =
                SobolFrame::ForResolution(scene.resolution.x, scene.resolution.y, ss.scramble);
    }
    if (ss.pattern == SamplePattern::Halton) {
        // pbrt-v4's halton: random digit permutations by default; pbrt-v4 refuses fastowen.
        const std::string r = randomization("permutedigits");
        HaltonScramble hs = HaltonScramble::PermuteDigits;
        if (r == "owen")
            hs = HaltonScramble::Owen;
        else if (r == "none")
            hs = HaltonScramble::None;
        else if (r != "permutedigits")
            throw badRandomization(r,
                                   "permutedigits, owen, none (pbrt-v4's halton has no fastowen)");
        ss.halton = HaltonFrame::ForResolution(scene.resolution.x, scene.resolution.y, hs, ss.seed);
    }
    WarnIgnoredRest(sp, diag, context,
                    DrawsCameraDims(ss.pattern)
                        ? "Prism reads its sample count, randomization and seed"
                        : "Prism reads only its sample count");
    if (ss.pattern == SamplePattern::Sobol && !replaced && spp > 0 && (spp & (spp - 1)) != 0) {
        // pbrt's SobolSampler takes a power of two samples per pixel (--spp is kept as given).
        const int rounded = int(uint32_t(1) << CeilLog2(uint64_t(spp)));
        const Param *p = sp.Find("pixelsamples");
        diag.Warn(p ? p->loc : loc, context + ": " + std::to_string(spp) +
                                        " samples per pixel rounded up to " +
                                        std::to_string(rounded) + ", as pbrt does");
        spp = rounded;
    }
    if (settings.spp > 0) spp = settings.spp;
    const int maxSpp = MaxSamplesPerPixel;
    if (spp <= 0 || spp > maxSpp)
        throw SceneError(desc.sampler.loc, "samples per pixel " + std::to_string(spp) +
                                               " out of range (1 to " + std::to_string(maxSpp) +
                                               ")");
    scene.sampler.spp = spp;
}

void BuildIntegratorSettings(BuildContext &ctx) {
    const SceneDescription &desc = ctx.desc;
    const BuildSettings &settings = ctx.settings;
    RenderScene &scene = ctx.scene;
    Diagnostics &diag = ctx.diag;
    const ParamSet &ip = desc.integrator.params;
    // --integrator replaces the scene's choice (its parameters still apply). A pbrt file
    // without an Integrator directive leaves the default of its version, pbrt-v3's "path" or
    // pbrt-v4's "volpath" (maxdepth 5 both), unless the settings name another default; OBJ and
    // glTF scenes set theirs ("distribution") without a location.
    const bool v4 = desc.pbrtVersion.version == 4;  // 3 for every file that is not pbrt
    const char *pbrtDefault = v4 ? "volpath" : "path";
    const bool unnamed = settings.integrator.empty() && !desc.integrator.loc.Valid() &&
                         desc.integrator.type == pbrtDefault;
    const std::string type = !settings.integrator.empty() ? settings.integrator
                             : unnamed && !settings.defaultIntegrator.empty()
                                 ? settings.defaultIntegrator
                                 : desc.integrator.type;
    std::string name = type;
    if (!settings.integrator.empty())
        scene.integratorWhy = "--integrator " + settings.integrator;
    else if (desc.integrator.loc.Valid())
        scene.integratorWhy = "Integrator " + Quote(type) + " at " + desc.integrator.loc.ToString();
    else if (type != pbrtDefault)
        scene.integratorWhy = "default of the scene's format";
    else
        scene.integratorWhy =
            std::string(v4 ? "pbrt-v4" : "pbrt-v3") + "'s default: the scene names no Integrator";
    int maxDepth = ip.GetInt("maxdepth", 5);
    // pbrt-v4's teaching integrators converge to the image of the one that stands in for them.
    struct StandIn {
        const char *name, *with, *why;
    };
    static constexpr StandIn kStandIns[] = {
        {"simplepath", "path", "the same image, as pbrt-v4's simplepath is path without MIS"},
        {"randomwalk", "path",
         "the same image but for perfect mirrors and glass, which "
         "pbrt-v4's random walk cannot follow and renders black"},
        {"simplevolpath", "volpath",
         "the same image where pbrt-v4 renders one, as pbrt-v4's simplevolpath is volpath "
         "without light sampling and stops at surfaces that scatter and at point, spot and "
         "distant lights"},
        {"lightpath", "path",
         "the same image but for what is seen in perfect mirrors and glass, "
         "which pbrt-v4's light tracing cannot reach and renders black"},
    };
    for (const StandIn &si : kStandIns) {
        if (name != si.name || !settings.integrator.empty()) continue;
        diag.Warn(desc.integrator.loc, "integrator " + Quote(type) + " is rendered with " +
                                           Quote(si.with) + ": " + si.why);
        ip.MarkUsed("samplelights");
        ip.MarkUsed("samplebsdf");
        name = si.with;
    }
    const bool known = std::find(IntegratorNames().begin(), IntegratorNames().end(), name) !=
                       IntegratorNames().end();
    if (!known) {
        // Only an Integrator the file names is worth a warning (pbrt's default is "path").
        if (desc.integrator.loc.Valid())
            diag.Warn(desc.integrator.loc,
                      "integrator " + Quote(type) + " is rendered with Whitted (maxdepth " +
                          std::to_string(settings.maxDepth >= 0 ? settings.maxDepth : maxDepth) +
                          ")");
        name = "whitted";
    }
    const DirectiveParams params(ip, diag, "integrator " + Quote(type), desc.integrator.loc);
    IntegratorInputs in{params,
                        desc.integrator.loc,
                        settings.glossySamples,
                        settings.spp,
                        scene.features.effects,
                        {},
                        {}};
    in.pbrtVersion = desc.pbrtVersion.version;
    in.lightSampler = settings.lightSampler;
    if (!settings.integrator.empty()) {
        in.why = "--integrator " + type;
    } else {
        in.why = "Integrator " + Quote(type);
        in.whyLoc = desc.integrator.loc;
    }
    scene.integrator = CreateIntegrator(name, in);
    if (!settings.lightSampler.empty() && name != "path" && name != "volpath")
        diag.Warn("--light-sampler has no effect on the " + name +
                  " integrator (path and volpath read it)");
    if (settings.maxDepth >= 0) maxDepth = settings.maxDepth;
    if (maxDepth < 0 || maxDepth > MaxTraceDepth)
        throw SceneError(desc.integrator.loc, "maxdepth " + std::to_string(maxDepth) +
                                                  " out of range (0 to " +
                                                  std::to_string(MaxTraceDepth) + ")");
    scene.trace.maxDepth = maxDepth;
    // The accuracy knobs are settings, not scene data; the command line checks them too.
    if (!(settings.rayCutoff >= 0) || !std::isfinite(settings.rayCutoff))
        throw SceneError("ray cutoff " + std::to_string(settings.rayCutoff) +
                         " must be a finite number >= 0");
    if (settings.offset.mode == OffsetMode::FixedEpsilon &&
        (!(settings.offset.epsilon > 0) || !std::isfinite(settings.offset.epsilon)))
        throw SceneError("offset epsilon " + std::to_string(settings.offset.epsilon) +
                         " must be a finite number > 0");
    scene.trace.rayCutoff = settings.rayCutoff;
    scene.offset = settings.offset;
}
}  // namespace prism
