// Parser for pbrt-v3 scene files (plus the common pbrt-v4 spellings). Syntax only, as
// pbrt-v4's parser.cpp: tokens become calls on a PbrtTarget, one per directive, with the
// positional arguments checked and the parameter lists as written (ParsedParameter). Include
// and Import are followed here (the file text comes from the shared reader of core/file_io.h);
// the graphics state, named objects and scopes are the target's business (scene_builder.h).
#pragma once

#include <string>

#include "core/error.h"
#include "scene/paramset.h"
#include "scene/scene_description.h"

namespace prism {

class MemoryBudget;

struct PbrtParseOptions {
    int maxIncludeDepth = 32;
    // When set, an Include/Import (or .spd spectrum file) that resolves outside the directory
    // of the top-level file is rejected; for fuzzing and untrusted input.
    bool confineIncludes = false;
    // When set, the top-level file (ParsePbrtFile), every included file and the parameters of
    // every shape are charged to it (core/memory.h); MemoryBudgetError once they exceed it.
    MemoryBudget *budget = nullptr;
    // The pbrt version whose rules apply (3 or 4); 0 detects it from the file
    // (scene/pbrt_version.h). --pbrt-version.
    int pbrtVersion = 0;
};

enum class ActiveTransformKind { StartTime, EndTime, All };

// Receives the directives of a pbrt file in order (as pbrt-v4's ParserTarget). Every call
// gets the location of its directive; parameter lists are passed as written.
class PbrtTarget {
  public:
    virtual ~PbrtTarget() = default;

    // Transforms and scopes.
    virtual void AttributeBegin(const FileLoc &loc) = 0;
    virtual void AttributeEnd(const FileLoc &loc) = 0;
    virtual void TransformBegin(const FileLoc &loc) = 0;
    virtual void TransformEnd(const FileLoc &loc) = 0;
    virtual void Translate(double dx, double dy, double dz, const FileLoc &loc) = 0;
    virtual void Scale(double sx, double sy, double sz, const FileLoc &loc) = 0;
    virtual void Rotate(double angle, double ax, double ay, double az, const FileLoc &loc) = 0;
    virtual void LookAt(double ex, double ey, double ez, double lx, double ly, double lz, double ux,
                        double uy, double uz, const FileLoc &loc) = 0;
    virtual void Transform(const double m[16], const FileLoc &loc) = 0;
    virtual void ConcatTransform(const double m[16], const FileLoc &loc) = 0;
    virtual void Identity(const FileLoc &loc) = 0;
    virtual void CoordinateSystem(const std::string &name, const FileLoc &loc) = 0;
    virtual void CoordSysTransform(const std::string &name, const FileLoc &loc) = 0;
    virtual void ActiveTransform(ActiveTransformKind kind, const FileLoc &loc) = 0;
    virtual void TransformTimes(double start, double end, const FileLoc &loc) = 0;
    virtual void ReverseOrientation(const FileLoc &loc) = 0;

    // Options block.
    virtual void Camera(const std::string &type, ParsedParameterVector params,
                        const FileLoc &loc) = 0;
    virtual void Film(const std::string &type, ParsedParameterVector params,
                      const FileLoc &loc) = 0;
    virtual void Sampler(const std::string &type, ParsedParameterVector params,
                         const FileLoc &loc) = 0;
    virtual void PixelFilter(const std::string &type, ParsedParameterVector params,
                             const FileLoc &loc) = 0;
    virtual void Integrator(const std::string &type, ParsedParameterVector params,
                            const FileLoc &loc) = 0;
    virtual void Accelerator(const std::string &type, ParsedParameterVector params,
                             const FileLoc &loc) = 0;
    virtual void Option(ParsedParameterVector params, const FileLoc &loc) = 0;
    // An Import directive (pbrt-v4), before the parser reads the file as it reads Include.
    virtual void Import(const std::string &file, const FileLoc &loc) {
        (void)file;
        (void)loc;
    }
    virtual void ColorSpace(const std::string &name, const FileLoc &loc) = 0;

    // World block.
    virtual void WorldBegin(const FileLoc &loc) = 0;
    virtual void WorldEnd(const FileLoc &loc) = 0;
    virtual void Material(const std::string &type, ParsedParameterVector params,
                          const FileLoc &loc) = 0;
    virtual void MakeNamedMaterial(const std::string &name, ParsedParameterVector params,
                                   const FileLoc &loc) = 0;
    virtual void NamedMaterial(const std::string &name, const FileLoc &loc) = 0;
    // `kind` is the texture's value type as written ("float", "spectrum", ...); `type` its
    // class ("imagemap", "checkerboard", ...).
    virtual void Texture(const std::string &name, const std::string &kind, const std::string &type,
                         ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void LightSource(const std::string &type, ParsedParameterVector params,
                             const FileLoc &loc) = 0;
    virtual void AreaLightSource(const std::string &type, ParsedParameterVector params,
                                 const FileLoc &loc) = 0;
    virtual void Shape(const std::string &type, ParsedParameterVector params,
                       const FileLoc &loc) = 0;
    virtual void ObjectBegin(const std::string &name, const FileLoc &loc) = 0;
    virtual void ObjectEnd(const FileLoc &loc) = 0;
    virtual void ObjectInstance(const std::string &name, const FileLoc &loc) = 0;
    virtual void MakeNamedMedium(const std::string &name, ParsedParameterVector params,
                                 const FileLoc &loc) = 0;
    // One name is both media (pbrt-v3); "" is no medium (vacuum).
    virtual void MediumInterface(const std::string &inside, const std::string &outside,
                                 const FileLoc &loc) = 0;
    virtual void Attribute(const std::string &target, ParsedParameterVector params,
                           const FileLoc &loc) = 0;
    // Prism extension (docs/FORMAT.md): constructive solid geometry. Targets that do not
    // implement it reject it.
    virtual void CSGBegin(const std::string &op, const FileLoc &loc) {
        throw SceneError(loc, "CSGBegin " + Quote(op) + " is not supported here");
    }
    virtual void CSGEnd(const FileLoc &loc) {
        throw SceneError(loc, "CSGEnd is not supported here");
    }

    // After the last directive of the top-level file.
    virtual void EndOfFiles() = 0;
};

// Parses `text` as the contents of `filename` (which names locations; relative Include paths
// resolve against its directory) and sends its directives to `target`. Throws SceneError for
// malformed input, unknown directives, directives after WorldEnd, unreadable includes,
// include cycles and includes nested deeper than opts.maxIncludeDepth.
void ParsePbrt(std::string text, const std::string &filename, PbrtTarget &target,
               const PbrtParseOptions &opts = {});

// Parses the scene file at `path` into a SceneDescription (through the SceneBuilder of
// scene_builder.h). Relative paths inside it (Include, .spd files) resolve against its
// directory, which is stored in SceneDescription::baseDir. Throws SceneError.
SceneDescription ParsePbrtFile(const std::string &path, Diagnostics &diag,
                               const PbrtParseOptions &opts = {});

// As ParsePbrtFile, for `text` given as if it were the contents of `filename` (which names
// locations and gives the base directory for includes; the file itself is not read).
SceneDescription ParsePbrtString(const std::string &text, const std::string &filename,
                                 Diagnostics &diag, const PbrtParseOptions &opts = {});

}  // namespace prism
