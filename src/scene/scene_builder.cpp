#include "scene/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/file_io.h"
#include "core/memory.h"
#include "scene/named_spectra.h"
#include "scene/spectrum.h"

namespace prism {

namespace {

const char *FrameName(int kind) {
    static const char *names[] = {"AttributeBegin", "TransformBegin", "ObjectBegin"};
    return names[kind];
}

// Transform constructors reject degenerate input (a zero scale, LookAt along "up") with
// std::invalid_argument; in a scene file that is an error at the directive.
template <typename F>
prism::Transform TransformOrThrow(const char *directive, const FileLoc &loc, F &&make) {
    try {
        return make();
    } catch (const std::invalid_argument &e) {
        throw SceneError(loc, std::string(directive) + ": " + e.what());
    }
}

std::string FormatNumber(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

}  // namespace

SceneBuilder::SceneBuilder(const std::string &filename, Diagnostics &diag,
                           const PbrtParseOptions &opts)
    : diag_(diag), opts_(opts) {
    scene_.format = "pbrt";
    scene_.sourceFile = filename;
    scene_.baseDir = DirectoryOf(filename);
}

// Parameters and entities.

ParamSet SceneBuilder::Params(ParsedParameterVector params) {
    return MakeParamSet(
        std::move(params),
        [this](const std::string &name, const FileLoc &loc) { return SpectrumFile(name, loc); },
        gs_.colorSpace);
}

SceneEntity SceneBuilder::Entity(const char *directive, const std::string &type,
                                 ParsedParameterVector params, const FileLoc &loc) {
    Observe(directive, type, params, loc);
    return SceneEntity{type, Params(std::move(params)), loc, gs_.colorSpace};
}

void SceneBuilder::Observe(const char *directive, const std::string &type,
                           const ParsedParameterVector &params, const FileLoc &loc) {
    std::string_view t = type;
    if (t.empty())
        for (const ParsedParameter &p : params)
            if (p.name == "type" && p.strings.size() == 1) t = p.strings[0];
    version_.Observe(directive, t, params, loc);
}

RGB SceneBuilder::SpectrumFile(const std::string &name, const FileLoc &loc) {
    // pbrt-v4 looks a name up among its named spectra before it looks for a file.
    std::string why;
    if (std::optional<RGB> named = NamedSpectrumRGB(name, &why)) return *named;
    if (IsNamedSpectrum(name)) {
        diag_.Warn(loc, why + "; using a constant 1");
        return RGB(1.f);
    }
    std::string path = ResolveScenePath(scene_.baseDir, name);
    auto cached = spdCache_.find(path);
    if (cached != spdCache_.end()) return cached->second;
    RGB result(1.f);
    std::string error;
    CheckReadConfinement(path, loc, "spectrum file", name);  // --confine: an error
    if (opts_.confineIncludes && !IsInsideDirectory(CanonicalPath(path), scene_.baseDir)) {
        diag_.Warn(loc, "spectrum file " + Quote(name) +
                            " is outside the scene directory; using a constant 1");
    } else if (std::optional<RGB> rgb = ReadSpdFile(path, name, &error, opts_.budget, loc)) {
        result = *rgb;
    } else {
        diag_.Warn(loc, error + "; using a constant 1");
    }
    spdCache_[path] = result;
    return result;
}

void SceneBuilder::CheckWorld(const char *directive, const FileLoc &loc) {
    if (!inWorld_) diag_.Warn(loc, std::string(directive) + " before WorldBegin");
}

bool SceneBuilder::OptionAllowed(const char *directive, const FileLoc &loc) {
    if (!inWorld_) return true;
    diag_.Warn(loc, std::string(directive) + " inside the world block is ignored");
    return false;
}

// Transforms and scopes.

void SceneBuilder::ApplyTransform(const prism::Transform &t, bool replace) {
    if (applyToStart_) ctm_ = replace ? t : ctm_ * t;
    if (applyToEnd_) ctmEnd_ = replace ? t : ctmEnd_ * t;
    if (applyToStart_ != applyToEnd_) motionLoc_ = activeLoc_;
}

std::optional<TransformMotion> SceneBuilder::Motion() const {
    if (ctm_ == ctmEnd_) return std::nullopt;
    return TransformMotion{ctmEnd_, transformStartTime_, transformEndTime_, motionLoc_};
}

std::unordered_map<std::string, int> &SceneBuilder::Names(Namespace ns) {
    switch (ns) {
        case Namespace::Material:
            return namedMaterials_;
        case Namespace::FloatTexture:
            return floatTextures_;
        case Namespace::SpectrumTexture:
            return spectrumTextures_;
    }
    return namedMaterials_;
}

void SceneBuilder::DefineNamed(Namespace ns, const std::string &name, int index) {
    auto &map = Names(ns);
    auto it = map.find(name);
    std::optional<int> previous;
    if (it != map.end()) previous = it->second;
    // Only scoped definitions need undoing; top-level ones live to the end of the file.
    if (!frames_.empty()) undo_.push_back({ns, name, previous});
    map[name] = index;
}

// What one frame of the graphics-state stack holds: charged at its Begin, given back at its
// End, so a million nested AttributeBegin are refused at the one that does not fit.
uint64_t SceneBuilder::FrameBytes(const FileLoc &loc) const {
    return sizeof(Frame) + loc.file.size() + gs_.mediumInside.size() + gs_.mediumOutside.size() +
           gs_.mediumLoc.file.size() + motionLoc_.file.size();
}

void SceneBuilder::PushFrame(FrameKind kind, const FileLoc &loc) {
    const uint64_t bytes = opts_.budget ? FrameBytes(loc) : 0;
    if (opts_.budget) opts_.budget->Charge(bytes, FrameName(int(kind)), loc);
    frames_.push_back({kind, loc, ctm_, ctmEnd_, applyToStart_, applyToEnd_, motionLoc_, gs_,
                       undo_.size(), bytes});
}

void SceneBuilder::PopFrame(FrameKind kind, const char *directive, const FileLoc &loc) {
    if (frames_.empty())
        throw SceneError(loc, std::string(directive) + " without matching " + FrameName(int(kind)));
    if (frames_.back().kind != kind) {
        const Frame &top = frames_.back();
        throw SceneError(loc, std::string(directive) + " does not match " +
                                  FrameName(int(top.kind)) + " at " + top.loc.ToString());
    }
    Frame f = std::move(frames_.back());
    frames_.pop_back();
    if (opts_.budget) opts_.budget->Release(f.charged);
    ctm_ = f.ctm;
    ctmEnd_ = f.ctmEnd;
    applyToStart_ = f.applyToStart;
    applyToEnd_ = f.applyToEnd;
    motionLoc_ = f.motionLoc;
    if (kind == FrameKind::Transform) return;
    gs_ = f.gs;
    while (undo_.size() > f.undoMark) {
        UndoEntry &u = undo_.back();
        auto &map = Names(u.ns);
        if (u.previous)
            map[u.name] = *u.previous;
        else
            map.erase(u.name);
        undo_.pop_back();
    }
}

void SceneBuilder::WarnUnclosedFrames() {
    for (const Frame &f : frames_)
        if (f.kind != FrameKind::Object)
            diag_.Warn(f.loc,
                       std::string(FrameName(int(f.kind))) + " without matching " +
                           (f.kind == FrameKind::Attribute ? "AttributeEnd" : "TransformEnd"));
}

void SceneBuilder::AttributeBegin(const FileLoc &loc) { PushFrame(FrameKind::Attribute, loc); }

void SceneBuilder::AttributeEnd(const FileLoc &loc) {
    PopFrame(FrameKind::Attribute, "AttributeEnd", loc);
}

void SceneBuilder::TransformBegin(const FileLoc &loc) { PushFrame(FrameKind::Transform, loc); }

void SceneBuilder::TransformEnd(const FileLoc &loc) {
    PopFrame(FrameKind::Transform, "TransformEnd", loc);
}

void SceneBuilder::Translate(double dx, double dy, double dz, const FileLoc &) {
    ApplyTransform(prism::Translate({dx, dy, dz}), false);
}

void SceneBuilder::Scale(double sx, double sy, double sz, const FileLoc &loc) {
    ApplyTransform(TransformOrThrow("Scale", loc, [&] { return prism::Scale(sx, sy, sz); }), false);
}

void SceneBuilder::Rotate(double angle, double ax, double ay, double az, const FileLoc &loc) {
    if (ax == 0 && ay == 0 && az == 0) throw SceneError(loc, "Rotate axis must not be zero");
    ApplyTransform(prism::Rotate(angle, {ax, ay, az}), false);
}

void SceneBuilder::LookAt(double ex, double ey, double ez, double lx, double ly, double lz,
                          double ux, double uy, double uz, const FileLoc &loc) {
    ApplyTransform(
        TransformOrThrow("LookAt", loc,
                         [&] {
                             return prism::LookAt({ex, ey, ez}, {lx, ly, lz}, {ux, uy, uz});
                         }),
        false);
}

void SceneBuilder::Transform(const double m[16], const FileLoc &loc) {
    ApplyTransform(TransformOrThrow("Transform", loc, [&] { return FromPbrtMatrix(m); }), true);
}

void SceneBuilder::ConcatTransform(const double m[16], const FileLoc &loc) {
    ApplyTransform(TransformOrThrow("ConcatTransform", loc, [&] { return FromPbrtMatrix(m); }),
                   false);
}

void SceneBuilder::Identity(const FileLoc &) { ApplyTransform(prism::Transform(), true); }

void SceneBuilder::CoordinateSystem(const std::string &name, const FileLoc &) {
    namedCoordSys_[name] = {ctm_, ctmEnd_};
}

void SceneBuilder::CoordSysTransform(const std::string &name, const FileLoc &loc) {
    auto cs = namedCoordSys_.find(name);
    if (cs == namedCoordSys_.end())
        throw SceneError(loc, "unknown coordinate system " + Quote(name));
    // Each active CTM takes the named system's transform at its own time.
    if (applyToStart_) ctm_ = cs->second.first;
    if (applyToEnd_) ctmEnd_ = cs->second.second;
    if (applyToStart_ != applyToEnd_) motionLoc_ = activeLoc_;
}

void SceneBuilder::ActiveTransform(ActiveTransformKind kind, const FileLoc &loc) {
    applyToStart_ = kind != ActiveTransformKind::EndTime;
    applyToEnd_ = kind != ActiveTransformKind::StartTime;
    if (kind != ActiveTransformKind::All) activeLoc_ = loc;
}

void SceneBuilder::TransformTimes(double start, double end, const FileLoc &loc) {
    if (!std::isfinite(start) || !std::isfinite(end))
        throw SceneError(loc, "TransformTimes must be finite");
    if (end < start)
        throw SceneError(loc, "TransformTimes end time " + FormatNumber(end) +
                                  " is before the start time " + FormatNumber(start));
    transformStartTime_ = start;
    transformEndTime_ = end;
}

void SceneBuilder::ReverseOrientation(const FileLoc &) {
    gs_.reverseOrientation = !gs_.reverseOrientation;
}

// Options block.

void SceneBuilder::Camera(const std::string &type, ParsedParameterVector params,
                          const FileLoc &loc) {
    SceneEntity e = Entity("Camera", type, std::move(params), loc);
    if (!OptionAllowed("Camera", loc)) return;
    CameraDesc &cam = scene_.camera;
    static_cast<SceneEntity &>(cam) = std::move(e);
    cam.cameraFromWorld = ctm_;
    cam.motion = Motion();
    cam.specified = true;
    // pbrt-v3: the camera is in the current outside medium (resolved at the end of the files,
    // so the medium may be defined after the Camera directive).
    cameraMedium_ = gs_.mediumOutside;
    cam.mediumLoc = gs_.mediumLoc;
    // As pbrt-v3 pbrtCamera: "camera" names the camera-to-world frame.
    namedCoordSys_["camera"] = {ctm_.Inverse(), ctmEnd_.Inverse()};
}

void SceneBuilder::Film(const std::string &type, ParsedParameterVector params, const FileLoc &loc) {
    SceneEntity e = Entity("Film", type, std::move(params), loc);
    if (OptionAllowed("Film", loc)) scene_.film = std::move(e);
}

void SceneBuilder::Sampler(const std::string &type, ParsedParameterVector params,
                           const FileLoc &loc) {
    SceneEntity e = Entity("Sampler", type, std::move(params), loc);
    if (OptionAllowed("Sampler", loc)) scene_.sampler = std::move(e);
}

void SceneBuilder::PixelFilter(const std::string &type, ParsedParameterVector params,
                               const FileLoc &loc) {
    SceneEntity e = Entity("PixelFilter", type, std::move(params), loc);
    if (OptionAllowed("PixelFilter", loc)) scene_.filter = std::move(e);
}

void SceneBuilder::Integrator(const std::string &type, ParsedParameterVector params,
                              const FileLoc &loc) {
    SceneEntity e = Entity("Integrator", type, std::move(params), loc);
    if (OptionAllowed("Integrator", loc)) scene_.integrator = std::move(e);
}

void SceneBuilder::Accelerator(const std::string &type, ParsedParameterVector params,
                               const FileLoc &loc) {
    // Embree builds its own BVH: the parameters are checked and dropped, with a warning.
    SceneEntity e = Entity("Accelerator", type, std::move(params), loc);
    if (!OptionAllowed("Accelerator", loc)) return;
    const std::string context = "Accelerator " + Quote(type);
    diag_.Warn(loc, context + " is replaced by Embree's BVH");
    WarnIgnoredRest(e.params, diag_, context, "Embree builds its own BVH");
}

void SceneBuilder::Option(ParsedParameterVector params, const FileLoc &loc) {
    version_.Note(4, "Option", loc);
    ParamSet ps = Params(std::move(params));
    for (const Param &p : ps.Params()) scene_.options.Add(p);
}

void SceneBuilder::Import(const std::string &, const FileLoc &loc) {
    version_.Note(4, "Import", loc);
}

// World block.

void SceneBuilder::WorldBegin(const FileLoc &loc) {
    if (inWorld_) throw SceneError(loc, "WorldBegin inside the world block");
    inWorld_ = true;
    applyToStart_ = applyToEnd_ = true;
    ctm_ = ctmEnd_ = prism::Transform();
    namedCoordSys_["world"] = {ctm_, ctmEnd_};
}

void SceneBuilder::WorldEnd(const FileLoc &) {
    WarnUnclosedFrames();
    worldEnded_ = true;
}

void SceneBuilder::Material(const std::string &type, ParsedParameterVector params,
                            const FileLoc &loc) {
    CheckWorld("Material", loc);
    MaterialDesc m;
    static_cast<SceneEntity &>(m) = Entity("Material", type, std::move(params), loc);
    AddAttributes(m.params, AttributeTarget::Material);
    gs_.material = int(scene_.materials.size());
    scene_.materials.push_back(std::move(m));
}

void SceneBuilder::MakeNamedMaterial(const std::string &name, ParsedParameterVector params,
                                     const FileLoc &loc) {
    CheckWorld("MakeNamedMaterial", loc);
    MaterialDesc m;
    m.name = name;
    Observe("MakeNamedMaterial", "", params, loc);
    m.params = Params(std::move(params));
    AddAttributes(m.params, AttributeTarget::Material);
    m.loc = loc;
    const Param *type = m.params.Find("type");
    if (!type || type->type != ParamType::String || type->strings.size() != 1)
        throw SceneError(
            loc, "MakeNamedMaterial " + Quote(m.name) + " needs a \"string type\" parameter");
    m.type = type->strings[0];
    m.params.MarkUsed("type");
    if (namedMaterials_.count(m.name))
        diag_.Warn(loc, "named material " + Quote(m.name) + " redefined");
    DefineNamed(Namespace::Material, m.name, int(scene_.materials.size()));
    scene_.materials.push_back(std::move(m));
}

void SceneBuilder::NamedMaterial(const std::string &name, const FileLoc &loc) {
    auto nm = namedMaterials_.find(name);
    if (nm == namedMaterials_.end()) throw SceneError(loc, "unknown named material " + Quote(name));
    gs_.material = nm->second;
}

void SceneBuilder::Texture(const std::string &name, const std::string &kind,
                           const std::string &type, ParsedParameterVector params,
                           const FileLoc &loc) {
    CheckWorld("Texture", loc);
    TextureDesc t;
    t.name = name;
    if (kind == "float")
        t.isFloat = true;
    else if (kind != "spectrum" && kind != "color" && kind != "rgb")
        throw SceneError(loc, "texture " + Quote(t.name) + ": unknown texture type " + Quote(kind) +
                                  " (expected \"float\" or \"spectrum\")");
    t.type = type;
    Observe("Texture", type, params, loc);
    t.params = Params(std::move(params));
    AddAttributes(t.params, AttributeTarget::Texture);
    t.loc = loc;
    t.worldFromTexture = ctm_;
    // The textures it refers to are defined already (by name, in either namespace: the
    // parameter decides which, and the larger cost is the safe one).
    TextureCost cost;
    for (const Param &p : t.params.Params()) {
        if (p.type != ParamType::Texture) continue;
        for (const std::string &ref : p.strings) {
            for (const auto *names : {&floatTextures_, &spectrumTextures_}) {
                auto it = names->find(ref);
                if (it == names->end()) continue;
                const TextureCost &c = textureCosts_[size_t(it->second)];
                cost.depth = std::max(cost.depth, c.depth + 1);
                cost.lookups = std::min(cost.lookups + c.lookups, kMaxTextureLookups + 1);
            }
        }
    }
    if (cost.depth > kMaxTextureDepth)
        throw SceneError(loc, "texture " + Quote(t.name) +
                                  ": textures refer to textures more than " +
                                  std::to_string(kMaxTextureDepth) + " levels deep");
    if (cost.lookups > kMaxTextureLookups)
        throw SceneError(loc, "texture " + Quote(t.name) +
                                  ": one lookup would evaluate more than " +
                                  std::to_string(kMaxTextureLookups) +
                                  " textures (textures referred to more than once multiply)");
    textureCosts_.push_back(cost);
    Namespace ns = t.isFloat ? Namespace::FloatTexture : Namespace::SpectrumTexture;
    if (Names(ns).count(t.name)) diag_.Warn(loc, "texture " + Quote(t.name) + " redefined");
    DefineNamed(ns, t.name, int(scene_.textures.size()));
    scene_.textures.push_back(std::move(t));
}

void SceneBuilder::LightSource(const std::string &type, ParsedParameterVector params,
                               const FileLoc &loc) {
    CheckWorld("LightSource", loc);
    LightDesc l;
    static_cast<SceneEntity &>(l) = Entity("LightSource", type, std::move(params), loc);
    AddAttributes(l.params, AttributeTarget::Light);
    l.worldFromLight = ctm_;
    l.medium = MediumIndex(gs_.mediumOutside, gs_.mediumLoc);
    scene_.lights.push_back(std::move(l));
}

void SceneBuilder::AreaLightSource(const std::string &type, ParsedParameterVector params,
                                   const FileLoc &loc) {
    CheckWorld("AreaLightSource", loc);
    AreaLightDesc a;
    static_cast<SceneEntity &>(a) = Entity("AreaLightSource", type, std::move(params), loc);
    AddAttributes(a.params, AttributeTarget::Light);
    gs_.areaLight = int(scene_.areaLights.size());
    scene_.areaLights.push_back(std::move(a));
}

void SceneBuilder::Shape(const std::string &type, ParsedParameterVector params,
                         const FileLoc &loc) {
    CheckWorld("Shape", loc);
    ShapeDesc s;
    static_cast<SceneEntity &>(s) = Entity("Shape", type, std::move(params), loc);
    AddAttributes(s.params, AttributeTarget::Shape);
    // The shape's description (its transforms, names and locations, about 600 bytes) and its
    // parameters (meshes given inline as "trianglemesh" arrays) live until the render: an
    // Include fan-out of parameterless shapes is refused at the shape that does not fit.
    if (opts_.budget) opts_.budget->Charge(ShapeDescBytes(s), "shape " + Quote(type), loc);
    s.worldFromObject = ctm_;
    s.motion = Motion();
    s.reverseOrientation = gs_.reverseOrientation;
    s.material = gs_.material;
    s.areaLight = gs_.areaLight;
    s.mediumInside = MediumIndex(gs_.mediumInside, gs_.mediumLoc);
    s.mediumOutside = MediumIndex(gs_.mediumOutside, gs_.mediumLoc);
    s.mediumLoc = gs_.mediumLoc;
    if (!csgStack_.empty()) {
        CsgDesc &node = csgStack_.back();
        s.directiveIndex = shapeCount_++;
        node.operands.push_back({true, int(node.shapes.size())});
        node.shapes.push_back(std::move(s));
    } else if (currentObject_) {
        s.directiveIndex = int(currentObject_->shapes.size());
        currentObject_->shapes.push_back(std::move(s));
    } else {
        s.directiveIndex = shapeCount_++;
        scene_.shapes.push_back(std::move(s));
    }
}

void SceneBuilder::ObjectBegin(const std::string &name, const FileLoc &loc) {
    CheckWorld("ObjectBegin", loc);
    if (currentObject_)
        throw SceneError(loc, "ObjectBegin inside ObjectBegin " + Quote(currentObject_->name) +
                                  " (started at " + currentObject_->loc.ToString() + ")");
    if (!csgStack_.empty())
        throw SceneError(loc, "ObjectBegin inside CSGBegin (at " + csgStack_.back().loc.ToString() +
                                  ") is not supported");
    if (FindObject(scene_, name)) throw SceneError(loc, "object " + Quote(name) + " redefined");
    // pbrt-v3 pbrtObjectBegin also begins an attribute scope.
    PushFrame(FrameKind::Object, loc);
    currentObject_ = ObjectDesc{name, loc, {}};
}

void SceneBuilder::ObjectEnd(const FileLoc &loc) {
    if (!currentObject_) throw SceneError(loc, "ObjectEnd without matching ObjectBegin");
    PopFrame(FrameKind::Object, "ObjectEnd", loc);
    scene_.objects.push_back(std::move(*currentObject_));
    currentObject_.reset();
}

void SceneBuilder::ObjectInstance(const std::string &name, const FileLoc &loc) {
    CheckWorld("ObjectInstance", loc);
    if (currentObject_)
        throw SceneError(loc, "ObjectInstance inside ObjectBegin " + Quote(currentObject_->name));
    if (!csgStack_.empty())
        throw SceneError(loc, "ObjectInstance cannot be a CSG operand (CSGBegin at " +
                                  csgStack_.back().loc.ToString() + ")");
    if (!FindObject(scene_, name)) throw SceneError(loc, "unknown object " + Quote(name));
    // Each instance holds its transforms and names: a million ObjectInstance lines are
    // refused at the one that does not fit.
    if (opts_.budget)
        opts_.budget->Charge(sizeof(InstanceDesc) + name.size() + loc.file.size(),
                             "ObjectInstance " + Quote(name), loc);
    scene_.instances.push_back({name, ctm_, Motion(), loc});
}

// CSG (Prism extension, docs/FORMAT.md). A node is not a graphics-state scope: operands take
// the CTM, material and orientation current at their own Shape directive.
void SceneBuilder::CSGBegin(const std::string &op, const FileLoc &loc) {
    CheckWorld("CSGBegin", loc);
    if (op != "union" && op != "intersection" && op != "difference")
        throw SceneError(loc, "unknown CSG operation " + Quote(op) +
                                  " (expected \"union\", \"intersection\" or \"difference\")");
    if (currentObject_)
        throw SceneError(loc, "CSGBegin inside ObjectBegin " + Quote(currentObject_->name) +
                                  " is not supported");
    if (csgStack_.size() >= size_t(kMaxCsgDepth))
        throw SceneError(loc, "CSG nodes nest more than " + std::to_string(kMaxCsgDepth) +
                                  " levels deep (outermost CSGBegin at " +
                                  csgStack_.front().loc.ToString() + ")");
    CsgDesc node;
    node.op = op;
    node.loc = loc;
    csgStack_.push_back(std::move(node));
}

void SceneBuilder::CSGEnd(const FileLoc &loc) {
    if (csgStack_.empty()) throw SceneError(loc, "CSGEnd without matching CSGBegin");
    CsgDesc node = std::move(csgStack_.back());
    csgStack_.pop_back();
    if (node.operands.empty())
        throw SceneError(node.loc,
                         "CSGBegin " + Quote(node.op) + " has no operands (empty CSG node)");
    if (csgStack_.empty()) {
        scene_.csg.push_back(std::move(node));
    } else {
        CsgDesc &parent = csgStack_.back();
        parent.operands.push_back({false, int(parent.children.size())});
        parent.children.push_back(std::move(node));
    }
}

void SceneBuilder::EndOfFiles() {
    PbrtVersionChoice &v = scene_.pbrtVersion;
    v = version_.Choose(opts_.pbrtVersion);
    // pbrt-v4's defaults where the file names no Sampler or Integrator.
    if (v.version == 4 && !scene_.sampler.loc.Valid()) scene_.sampler.type = "zsobol";
    if (v.version == 4 && !scene_.integrator.loc.Valid()) scene_.integrator.type = "volpath";
    if (!cameraMedium_.empty())
        scene_.camera.medium = MediumIndex(cameraMedium_, scene_.camera.mediumLoc);
    if (!csgStack_.empty())
        throw SceneError(csgStack_.back().loc, "CSGBegin without matching CSGEnd");
    if (currentObject_) {
        diag_.Warn(currentObject_->loc, "ObjectBegin without matching ObjectEnd");
        scene_.objects.push_back(std::move(*currentObject_));
        currentObject_.reset();
    }
    if (!worldEnded_) WarnUnclosedFrames();
}

}  // namespace prism
