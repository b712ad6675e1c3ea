// The pbrt graphics state, as pbrt-v4's BasicSceneBuilder: receives the directives of a pbrt
// file from the parser (pbrt_parser.h) and records them as a plain SceneDescription. It keeps
// the current transform, material, area light and ReverseOrientation, the AttributeBegin/End
// and TransformBegin/End scopes, named materials, textures and coordinate systems, and the
// ObjectBegin/End definitions; typed parameters are converted by MakeParamSet (paramset.h).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "scene/pbrt_parser.h"

namespace prism {

// How deep scenes may nest what is later walked recursively (the build, the destructors and
// every ray's CSG crossings and texture lookups): each limit is a SceneError at the directive
// that goes past it. Real scenes stay far below; a small file past them overflowed the stack.
inline constexpr int kMaxCsgDepth = 256;      // CSGBegin inside CSGBegin
inline constexpr int kMaxTextureDepth = 256;  // a texture referring to a texture referring ...
// Textures one lookup may evaluate, counting a texture each time it is reached: a chain that
// refers twice to the texture before it doubles at each step (2^100 evaluations per lookup).
inline constexpr uint64_t kMaxTextureLookups = 65536;

class SceneBuilder final : public PbrtTarget {
  public:
    // `filename` is the top-level file: it names the scene and its directory is the base of
    // relative paths (.spd files here; Include in the parser).
    SceneBuilder(const std::string &filename, Diagnostics &diag, const PbrtParseOptions &opts = {});

    // The scene, once the parser has called EndOfFiles().
    SceneDescription Result() { return std::move(scene_); }

    void AttributeBegin(const FileLoc &loc) override;
    void AttributeEnd(const FileLoc &loc) override;
    void TransformBegin(const FileLoc &loc) override;
    void TransformEnd(const FileLoc &loc) override;
    void Translate(double dx, double dy, double dz, const FileLoc &loc) override;
    void Scale(double sx, double sy, double sz, const FileLoc &loc) override;
    void Rotate(double angle, double ax, double ay, double az, const FileLoc &loc) override;
    void LookAt(double ex, double ey, double ez, double lx, double ly, double lz, double ux,
                double uy, double uz, const FileLoc &loc) override;
    void Transform(const double m[16], const FileLoc &loc) override;
    void ConcatTransform(const double m[16], const FileLoc &loc) override;
    void Identity(const FileLoc &loc) override;
    void CoordinateSystem(const std::string &name, const FileLoc &loc) override;
    void CoordSysTransform(const std::string &name, const FileLoc &loc) override;
    void ActiveTransform(ActiveTransformKind kind, const FileLoc &loc) override;
    void TransformTimes(double start, double end, const FileLoc &loc) override;
    void ReverseOrientation(const FileLoc &loc) override;

    void Camera(const std::string &type, ParsedParameterVector params, const FileLoc &loc) override;
    void Film(const std::string &type, ParsedParameterVector params, const FileLoc &loc) override;
    void Sampler(const std::string &type, ParsedParameterVector params,
                 const FileLoc &loc) override;
    void PixelFilter(const std::string &type, ParsedParameterVector params,
                     const FileLoc &loc) override;
    void Integrator(const std::string &type, ParsedParameterVector params,
                    const FileLoc &loc) override;
    void Accelerator(const std::string &type, ParsedParameterVector params,
                     const FileLoc &loc) override;
    void Option(ParsedParameterVector params, const FileLoc &loc) override;
    void Import(const std::string &file, const FileLoc &loc) override;
    void ColorSpace(const std::string &name, const FileLoc &loc) override;

    void WorldBegin(const FileLoc &loc) override;
    void WorldEnd(const FileLoc &loc) override;
    void Material(const std::string &type, ParsedParameterVector params,
                  const FileLoc &loc) override;
    void MakeNamedMaterial(const std::string &name, ParsedParameterVector params,
                           const FileLoc &loc) override;
    void NamedMaterial(const std::string &name, const FileLoc &loc) override;
    void Texture(const std::string &name, const std::string &kind, const std::string &type,
                 ParsedParameterVector params, const FileLoc &loc) override;
    void LightSource(const std::string &type, ParsedParameterVector params,
                     const FileLoc &loc) override;
    void AreaLightSource(const std::string &type, ParsedParameterVector params,
                         const FileLoc &loc) override;
    void Shape(const std::string &type, ParsedParameterVector params, const FileLoc &loc) override;
    void ObjectBegin(const std::string &name, const FileLoc &loc) override;
    void ObjectEnd(const FileLoc &loc) override;
    void ObjectInstance(const std::string &name, const FileLoc &loc) override;
    void MakeNamedMedium(const std::string &name, ParsedParameterVector params,
                         const FileLoc &loc) override;
    void MediumInterface(const std::string &inside, const std::string &outside,
                         const FileLoc &loc) override;
    void Attribute(const std::string &target, ParsedParameterVector params,
                   const FileLoc &loc) override;
    void CSGBegin(const std::string &op, const FileLoc &loc) override;
    void CSGEnd(const FileLoc &loc) override;

    void EndOfFiles() override;

  private:
    // What AttributeBegin/End saves besides the transform and the named definitions.
    struct GraphicsState {
        int material = -1;
        int areaLight = -1;
        bool reverseOrientation = false;
        // MediumInterface: the media's names ("" none) and the directive.
        std::string mediumInside, mediumOutside;
        FileLoc mediumLoc;
        // pbrt-v4's Attribute defaults per target (AttributeTarget), shared until changed:
        // an AttributeBegin copies pointers, not parameters.
        std::array<std::shared_ptr<const std::vector<Param>>, 5> attributes;
        ColorSpaceId colorSpace = ColorSpaceId::SRGB;  // pbrt-v4's ColorSpace
    };
    // Attribute "shape" | "light" | "material" | "medium" | "texture".
    enum class AttributeTarget { Shape, Light, Material, Medium, Texture };
    enum class FrameKind { Attribute, Transform, Object };
    struct Frame {
        FrameKind kind;
        FileLoc loc;
        prism::Transform ctm, ctmEnd;
        bool applyToStart, applyToEnd;
        FileLoc motionLoc;
        GraphicsState gs;
        size_t undoMark;       // size of the named-definition undo log when the frame was pushed
        uint64_t charged = 0;  // what PushFrame charged to the budget (FrameBytes)
    };
    // Named materials and textures are scoped by AttributeBegin/End. Instead of copying the
    // maps at every AttributeBegin (real scenes have tens of thousands), definitions are
    // logged and undone when their scope closes.
    enum class Namespace { Material, FloatTexture, SpectrumTexture };
    struct UndoEntry {
        Namespace ns;
        std::string name;
        std::optional<int> previous;
    };

    uint64_t FrameBytes(const FileLoc &loc) const;
    ParamSet Params(ParsedParameterVector params);
    // `directive` names the directive for the version detector (pbrt_version.h).
    SceneEntity Entity(const char *directive, const std::string &type, ParsedParameterVector params,
                       const FileLoc &loc);
    // Adds the Attribute defaults of `target` that `ps` does not set itself, as pbrt-v4 looks
    // an entity's parameters up before its attributes (scene_builder_attributes.cpp).
    void AddAttributes(ParamSet &ps, AttributeTarget target) const;
    // Shows a directive to the version detector; an empty `type` is read from the directive's
    // "string type" parameter (MakeNamedMaterial, MakeNamedMedium).
    void Observe(const char *directive, const std::string &type,
                 const ParsedParameterVector &params, const FileLoc &loc);
    RGB SpectrumFile(const std::string &name, const FileLoc &loc);
    // An options-block entity (Camera, Film, ...): false, with a warning, inside the world.
    bool OptionAllowed(const char *directive, const FileLoc &loc);
    void CheckWorld(const char *directive, const FileLoc &loc);
    void ApplyTransform(const prism::Transform &t, bool replace);
    void PushFrame(FrameKind kind, const FileLoc &loc);
    void PopFrame(FrameKind kind, const char *directive, const FileLoc &loc);
    void DefineNamed(Namespace ns, const std::string &name, int index);
    std::unordered_map<std::string, int> &Names(Namespace ns);
    void WarnUnclosedFrames();
    // The CTM's end-time transform and times for an entity declared now (empty if static).
    std::optional<TransformMotion> Motion() const;
    // The index of the medium named `name` ("": -1), or an error at the MediumInterface
    // directive `loc` that named it (scene_builder_media.cpp).
    int MediumIndex(const std::string &name, const FileLoc &loc) const;

    SceneDescription scene_;
    Diagnostics &diag_;
    PbrtParseOptions opts_;

    // pbrt-v3's two CTMs: ctm_ at the start time, ctmEnd_ at the end time; ActiveTransform
    // chooses which ones the transform directives change.
    prism::Transform ctm_, ctmEnd_;
    bool applyToStart_ = true, applyToEnd_ = true;
    FileLoc activeLoc_;  // the last ActiveTransform StartTime/EndTime
    FileLoc motionLoc_;  // the ActiveTransform in effect when the two CTMs last diverged
    double transformStartTime_ = 0, transformEndTime_ = 1;  // TransformTimes
    GraphicsState gs_;
    std::vector<Frame> frames_;
    std::vector<UndoEntry> undo_;
    std::unordered_map<std::string, int> namedMaterials_, floatTextures_, spectrumTextures_;
    std::unordered_map<std::string, std::pair<prism::Transform, prism::Transform>> namedCoordSys_;
    std::optional<ObjectDesc> currentObject_;
    std::vector<CsgDesc> csgStack_;  // open CSGBegin nodes, innermost last
    // Per texture (scene_.textures' index): the longest chain of textures it refers to, itself
    // included, and how many textures one lookup of it evaluates at most (kMaxTexture*).
    struct TextureCost {
        int depth = 1;
        uint64_t lookups = 1;
    };
    std::vector<TextureCost> textureCosts_;
    std::unordered_map<std::string, RGB> spdCache_;
    PbrtVersionDetector version_;
    // Named media are global, as in pbrt-v3 (not scoped by AttributeBegin/End).
    std::unordered_map<std::string, int> namedMedia_;
    std::string cameraMedium_;  // the outside medium at Camera, resolved at EndOfFiles
    bool inWorld_ = false, worldEnded_ = false;
    int shapeCount_ = 0;
};

}  // namespace prism
