#include "app/aov_output.h"

#include <algorithm>

#include "app/common.h"
#include "app/shape_lookup.h"
#include "core/file_io.h"
#include "image/image_io.h"

namespace prism {

namespace {

std::string JsonEscape(const std::string &s) {
    std::string out;
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) < 0x20) continue;
        out += c;
    }
    return out;
}

}  // namespace

void CheckAovOption(const std::string &aovOption, const std::string &output) {
    if (aovOption.empty()) return;
    std::vector<Aov> aovs;
    std::string error;
    if (!ParseAovList(aovOption, &aovs, &error)) throw UsageError("--aov: " + error);
    if (!output.empty() && LowerExtension(output) != ".exr")
        throw UsageError("--aov writes a multi-channel EXR: the output must end in .exr (not " +
                         Quote(output) + ")");
}

std::vector<Aov> ChooseAovs(const std::string &aovOption, const RenderScene &scene,
                            const std::string &out, Diagnostics &diag) {
    const std::string &list = aovOption.empty() ? scene.filmAovs : aovOption;
    std::vector<Aov> aovs;
    std::string error;
    if (list.empty() || !ParseAovList(list, &aovs, &error)) return {};  // checked before
    if (LowerExtension(out) != ".exr") {
        if (!aovOption.empty())
            throw UsageError("--aov writes a multi-channel EXR: the output must end in .exr (not " +
                             Quote(out) + ")");
        diag.Warn("Film \"aovs\" are written only into EXR outputs; " + Quote(out) +
                  " gets the beauty alone");
        return {};
    }
    if (scene.integrator->RendersWholeFrame()) {
        // Its frame is not made of camera samples the AOVs could share (render/integrator.h).
        if (!aovOption.empty())
            throw UsageError("--aov: Integrator " + Quote(scene.IntegratorName()) +
                             " renders the frame as a whole and writes no AOVs");
        diag.Warn("Film \"aovs\" are not written: Integrator " + Quote(scene.IntegratorName()) +
                  " renders the frame as a whole");
        return {};
    }
    if (!scene.integrator->Traits().directAov && AovsNeedDirect(aovs)) {
        if (list != "all")
            throw UsageError(
                "the direct and indirect AOVs need an integrator that separates direct light "
                "(this render uses " +
                Quote(scene.IntegratorName()) + "; try --integrator whitted)");
        aovs.erase(std::remove_if(aovs.begin(), aovs.end(),
                                  [](Aov a) { return a == Aov::Direct || a == Aov::Indirect; }),
                   aovs.end());
        diag.Warn("AOVs direct and indirect are left out: Integrator " +
                  Quote(scene.IntegratorName()) + " does not separate direct light");
    }
    return aovs;
}

AovOutput::AovOutput(const SceneDescription &desc, const RenderScene &scene,
                     const std::vector<Aov> &aovs)
    : lookup_(std::make_unique<ShapeLookup>(desc, scene)),
      materials_(desc.materials.size()),
      instances_(desc.instances.size()) {
    const ShapeLookup *lookup = lookup_.get();
    AovIdFn ids = [lookup](const SurfaceInteraction &si, int *shape, int *material, int *instance) {
        ShapeDeclaration d = lookup->Find(si);
        *shape = d.shapeId;
        *material = d.materialId;
        *instance = d.instanceId;
    };
    frame_ = std::make_unique<AovFrame>(scene, aovs, std::move(ids));
}

AovOutput::~AovOutput() = default;

void AovOutput::Write(const std::string &out, const Image &beauty, float scale) const {
    const ShapeLookup &lookup = *lookup_;
    std::vector<AovLayer> layers = frame_->Layers();
    std::vector<NamedChannel> channels;
    std::vector<std::pair<std::string, std::string>> attributes;
    for (AovLayer &l : layers) {
        // Exposure scales radiance (and variance by its square), as it scales the beauty.
        if (scale != 1 && (l.aov == Aov::Direct || l.aov == Aov::Indirect))
            for (float &v : l.pixels) v *= scale;
        if (scale != 1 && l.aov == Aov::Variance)
            for (float &v : l.pixels) v *= scale * scale;
        for (size_t c = 0; c < l.channels.size(); ++c)
            channels.push_back({l.channels[c], l.pixels.data() + c, l.channels.size()});
        // The manifest of an id layer: id → declaration, as JSON in a header attribute.
        auto manifest = [&](int n, auto label) {
            std::string json = "{";
            for (int id = 1; id <= n; ++id)
                json += (id > 1 ? ", \"" : "\"") + std::to_string(id) + "\": \"" +
                        JsonEscape(label(id)) + "\"";
            attributes.push_back(
                {std::string("prism/") + AovName(l.aov) + "/manifest", json + "}"});
        };
        if (l.aov == Aov::ShapeId)
            manifest(int(lookup.Declarations().size()),
                     [&](int id) { return lookup.ShapeLabel(id); });
        if (l.aov == Aov::MaterialId)
            manifest(int(materials_) + 1, [&](int id) { return lookup.MaterialLabel(id); });
        if (l.aov == Aov::InstanceId)
            manifest(int(instances_), [&](int id) { return lookup.InstanceLabel(id); });
    }
    WriteMultiChannelExr(out, beauty, channels, attributes);
}

}  // namespace prism
