#include "assembly/shapes.h"

#include <chrono>
#include <map>
#include <stdexcept>

#include "assembly/csg.h"
#include "assembly/lights.h"
#include "assembly/media.h"
#include "assembly/scene_effects.h"
#include "assembly/shape_factory.h"
#include "assembly/textures.h"
#include "core/memory.h"

namespace prism {

std::optional<AnimatedTransform> ShutterMotion(const BuildContext &ctx,
                                               const Transform *renderFromWorld,
                                               const Transform &worldFromX,
                                               const std::optional<TransformMotion> &motion,
                                               const FileLoc &loc, Transform *atOpen) {
    auto toRender = [&](const Transform &t) { return renderFromWorld ? *renderFromWorld * t : t; };
    if (!motion) {
        *atOpen = toRender(worldFromX);
        return std::nullopt;
    }
    AnimatedTransform anim;
    try {
        anim = AnimatedTransform(toRender(worldFromX), motion->startTime, toRender(motion->end),
                                 motion->endTime);
    } catch (const std::invalid_argument &e) {
        throw SceneError(loc, std::string("motion: ") + e.what());
    }
    if (!anim.MovesDuring(ctx.shutterOpen, ctx.shutterClose)) {
        // Still while the shutter is open (or the shutter takes no time): one transform.
        *atOpen = anim.Interpolate(ctx.shutterOpen);
        return std::nullopt;
    }
    AnimatedTransform shutter = anim.Remapped(ctx.shutterOpen, ctx.shutterClose);
    *atOpen = shutter.Interpolate(0);
    ctx.scene.features.effects.Enable(Effect::MotionBlur, "ActiveTransform", motion->loc);
    return shutter;
}

namespace {

// What the BVH estimate (core/memory.h EstimateBvhBytes) counts in an Accel: the triangles of
// its meshes, and one user primitive for each analytic shape, instance or curve segment.
uint64_t UserPrimsOf(const Accel &accel) {
    uint64_t n = 0;
    for (int i = 0; i < accel.NumShapes(); ++i)
        n += accel.Mesh(i) ? 0 : accel.Curves(i) ? accel.Curves(i)->NumSegments() : 1;
    return n;
}

struct ShapeBuilder : BuildStep {
    ShapeBuilder(BuildContext &ctx, MaterialBuilder &m) : BuildStep(ctx), materials(m) {}
    MaterialBuilder &materials;
    std::vector<const AreaLightDesc *> usedAreaLights;  // unused parameters reported at the end

    // Shape "(every shape)": the cut-outs (geometry/alpha.h), read here for each shape; the
    // glTF and OBJ readers write the Prism extensions. Parameters:
    //   alpha           texture   1         1 keeps the surface; a constant 0 removes it from
    //                                       every ray (pbrt-v3 cuts out only where alpha is
    //                                       exactly 0); a texture is a cut-out test on each hit
    //   shadowalpha     texture   alpha     the same, for shadow rays only
    //   alphamode       string    (none)    Prism: "mask" keeps a hit where alpha >= alphacutoff;
    //                                       "blend" is stochastic transparency: a hit is kept
    //                                       where alpha exceeds a hash of the ray and the
    //                                       primitive, for camera, secondary and shadow rays
    //                                       alike, so a surface of alpha a passes 1 - a of them
    //                                       and its shadow darkens by a on average
    //   alphacutoff     float     0.5       Prism: the "mask" threshold
    //   alphatexcoord   integer   0         Prism: the uv set the test reads (1: the mesh's "uv1")
    //   alphatransform  float[5]  (none)    Prism: a transform of the alpha texture's uv (offset
    //                                       u v, rotation in radians, scale u v), glTF's
    //                                       KHR_texture_transform
    unsigned VisibilityMask(const ShapeDesc &s, ShapeAlpha *cutouts) {
        const ParamSet &ps = s.params;
        float alpha = 1, shadowAlpha = 1;
        TexturePtr alphaTex, shadowTex;
        for (const char *n : {"alpha", "shadowalpha"}) {
            const Param *p = ps.Find(n);
            if (!p) continue;
            const bool isAlpha = std::string(n) == "alpha";
            if (p->type == ParamType::Texture) {
                TexturePtr t = TextureParam(ctx, ps, n, true, RGB(1));
                if (auto *c = dynamic_cast<const ConstantTexture *>(t.get()))
                    (isAlpha ? alpha : shadowAlpha) = c->Value().r;
                else
                    (isAlpha ? alphaTex : shadowTex) = t;
                scene.features.effects.Enable(Effect::Alpha, "\"" + std::string(n) + "\" texture",
                                              p->loc);
                continue;
            }
            (isAlpha ? alpha : shadowAlpha) = ps.GetFloat(n, 1.f);
        }
        if (!ps.Has("shadowalpha")) {
            shadowAlpha = alpha;
            shadowTex = alphaTex;
        }
        const std::string mode = ps.GetString("alphamode", "");
        if (!mode.empty() && mode != "mask" && mode != "blend")
            throw SceneError(ps.Find("alphamode")->loc,
                             "\"alphamode\" must be \"mask\" or \"blend\", not " + Quote(mode));
        const float cutoff = ps.GetFloat("alphacutoff", 0.5f);
        // A constant alpha between 0 and 1 is stochastic transparency in "blend" mode, for
        // camera and shadow rays.
        if (mode == "blend") {
            bool partial = false;
            if (!alphaTex && alpha > 0 && alpha < 1)
                alphaTex = Constant(RGB(alpha)), partial = true;
            if (!shadowTex && shadowAlpha > 0 && shadowAlpha < 1)
                shadowTex = Constant(RGB(shadowAlpha)), partial = true;
            if (partial)
                scene.features.effects.Enable(Effect::Alpha, "\"alphamode\" \"blend\"",
                                              ps.Find("alphamode")->loc);
        }
        // The uv set the test passes (the mesh's "uv1" for "alphatexcoord" 1); the texture
        // then reads it as uv (and as uv1, so a TexCoord1Texture reads the same).
        const int uvSet = ps.GetInt("alphatexcoord", 0);
        auto test = [&](TexturePtr t) {
            t = WithTexCoordParams(t, nullptr, ps, "alpha");
            auto a = std::make_shared<AlphaTest>();
            a->alpha = [t](const Vec2f &uv, const Vec3f &p) { return t->Evaluate({uv, p, uv}).r; };
            if (mode == "mask") a->cutoff = cutoff;
            a->stochastic = mode == "blend";
            a->uvSet = uvSet == 1 ? 1 : 0;
            return a;
        };
        if (alphaTex) cutouts->camera = test(alphaTex);
        if (shadowTex) cutouts->shadow = test(shadowTex);
        unsigned mask = AllRays;
        if (alpha == 0 && !alphaTex) mask &= ~CameraRays;
        if (shadowAlpha == 0 && !shadowTex) mask &= ~ShadowRays;
        return mask;
    }

    // Creates the geometry of one shape and adds it to `accel`; records its ShapeInfo in
    // `infos` (by accel shape index). Returns the shape index, or -1 if skipped.
    int AddShapeTo(Accel &accel, std::vector<ShapeInfo> &infos, const ShapeDesc &s,
                   const Transform &renderFromObject,
                   const std::optional<AnimatedTransform> &motion = std::nullopt) {
        ShapeFactoryContext fctx{desc, diag, settings.precision, &budget};
        ShapeGeometry geom = CreateShapeGeometry(s, renderFromObject, fctx);
        if (geom.Empty()) return -1;                           // skipped with a warning
        if (settings.replaceAnalyticShape && geom.analytic) {  // e.g. --tessellate N
            MeshCharge charge = [&](uint64_t meshBytes, uint64_t transientBytes) {
                std::string what = "shape " + Quote(s.type);
                budget.Check(meshBytes + transientBytes, what, s.loc);
                budget.Charge(meshBytes, what, s.loc);
            };
            try {
                if (auto twin = settings.replaceAnalyticShape(*geom.analytic, charge)) {
                    geom.mesh = std::move(twin);
                    geom.analytic.reset();
                }
            } catch (const std::length_error &e) {
                throw SceneError(s.loc, e.what());
            }
        }
        ShapeAlpha cutouts;
        unsigned mask = VisibilityMask(s, &cutouts);
        if (mask == 0) return -1;  // alpha 0: cut out entirely
        if (geom.curves && cutouts.Any()) {
            diag.Warn(s.loc, "alpha textures on curves are not supported; the curve is opaque");
            cutouts = {};
        }
        if (motion) AddMotion(s, geom, *motion, renderFromObject);
        int material = materials.MaterialForShape(s);
        // Normal maps read tangents: the mesh's own ("tangent"), else generated ones.
        if (geom.mesh && scene.materials[size_t(material)].normalMap && !geom.mesh->HasTangents())
            geom.mesh->GenerateTangents(scene.materials[size_t(material)].normalMapUVSet);
        s.params.ReportUnused(diag, "shape " + Quote(s.type));
        int index;
        if (geom.curves) {
            scene.features.curveSegments += geom.curves->NumSegments();
            index = accel.AddCurves(std::move(geom.curves), mask);
        } else if (geom.mesh) {
            scene.features.meshes++;
            scene.features.triangles += geom.mesh->NumTriangles();
            index = accel.AddMesh(std::move(geom.mesh), mask, std::move(cutouts));
        } else {
            scene.features.analyticShapes++;
            index = accel.AddAnalytic(std::move(geom.analytic), mask, std::move(cutouts));
        }
        if (int(infos.size()) <= index) infos.resize(size_t(index) + 1);
        infos[size_t(index)] = {material, -1, s.directiveIndex, s.type, -1};
        NoteShapeMedia(ctx, s, &infos[size_t(index)]);
        const Material &m = scene.materials[size_t(material)];
        accel.SetSurfaceNeeds(index, m.SurfaceNeeds());
        if (m.MayReflectSpecularly()) scene.features.specularReflection = true;
        if (m.MayTransmit()) scene.features.transmission = true;
        FileLoc materialLoc;
        std::string why = MaterialWhy(desc, s, &materialLoc);
        NoteMaterialEffects(ctx, m, why, materialLoc);
        return index;
    }

    // Motion blur: an analytic shape interpolates its transform per ray; a mesh gets Embree
    // time steps (vertices moved by the motion relative to the shutter's opening).
    void AddMotion(const ShapeDesc &s, ShapeGeometry &geom, const AnimatedTransform &motion,
                   const Transform &renderFromObject) {
        if (geom.analytic) {
            geom.analytic->SetMotion(motion);
            return;
        }
        const int n = MotionTimeSteps(motion);
        const Transform startFromRender = renderFromObject.Inverse();
        std::vector<Transform> steps;
        for (int k = 1; k < n; ++k)
            steps.push_back(motion.Interpolate(double(k) / (n - 1)) * startFromRender);
        if (geom.curves) {
            budget.Charge(uint64_t(n - 1) * geom.curves->MemoryBytes(),
                          "shape " + Quote(s.type) + " motion steps", s.loc);
            geom.curves->SetMotionSteps(steps);
            return;
        }
        // Each step after the first holds the positions (and normals) again.
        const TriangleMesh &m = *geom.mesh;
        budget.Charge(uint64_t(n - 1) * ((3 * m.NumVertices() + 1) * sizeof(float) +
                                         (m.HasNormals() ? m.NumVertices() * sizeof(Vec3f) : 0)),
                      "shape " + Quote(s.type) + " motion steps", s.loc);
        geom.mesh->SetMotionSteps(steps);
    }

    void AddShape(const ShapeDesc &s) {
        Transform renderFromObject;
        std::optional<AnimatedTransform> motion = ShutterMotion(
            ctx, &scene.renderFromWorld, s.worldFromObject, s.motion, s.loc, &renderFromObject);
        int index = AddShapeTo(*scene.accel, scene.shapes, s, renderFromObject, motion);
        if (index >= 0 && s.areaLight >= 0 && scene.accel->Curves(index)) {
            diag.Warn(s.loc,
                      "area lights on curves are not supported (pbrt-v3 stops with \"Curve::Sample "
                      "not implemented\"); the curve does not emit");
            return;
        }
        if (index >= 0 && s.areaLight >= 0 && motion) {
            diag.Warn(s.loc,
                      "area lights on moving shapes are not supported (as in pbrt-v3); the "
                      "shape does not emit");
            return;
        }
        if (index >= 0 && s.areaLight >= 0)
            if (const AreaLightDesc *a = AddAreaLight(ctx, s, index)) usedAreaLights.push_back(a);
    }

    // CSGBegin/CSGEnd: each top-level node is one analytic shape (one user geometry) whose
    // operands are looked up like the shapes of a prototype (ShapeInfo::prototype).
    void AddCsg(const CsgDesc &node) {
        std::vector<ShapeInfo> operands;
        std::unique_ptr<CsgShape> csg = BuildCsgShape(ctx, materials, node, &operands);
        unsigned needs = NeedNone;
        for (const ShapeInfo &o : operands) {
            const Material &m = scene.materials[size_t(o.material)];
            needs |= m.SurfaceNeeds();
            if (m.MayReflectSpecularly()) scene.features.specularReflection = true;
            if (m.MayTransmit()) scene.features.transmission = true;
            NoteMaterialEffects(ctx, m, "material " + Quote(m.typeName) + " of a CSG operand",
                                node.loc);
        }
        int index = scene.accel->AddAnalytic(std::move(csg));
        scene.accel->SetSurfaceNeeds(index, needs);
        scene.prototypes.push_back(std::move(operands));
        if (int(scene.shapes.size()) <= index) scene.shapes.resize(size_t(index) + 1);
        ShapeInfo info;
        info.type = "csg";
        info.directiveIndex = -1;  // hits report their operand's (RenderScene::Info)
        info.prototype = int(scene.prototypes.size()) - 1;
        scene.shapes[size_t(index)] = info;
        scene.features.csgNodes++;
        scene.features.effects.Enable(Effect::Csg, "CSGBegin " + Quote(node.op), node.loc);
    }

    // ObjectInstance: each ObjectBegin group becomes one committed prototype, shared by all
    // its instances (Embree instances; one level, as in pbrt-v3).
    std::map<std::string, std::pair<std::shared_ptr<const Accel>, int>> prototypeOf;

    void AddInstance(const InstanceDesc &inst) {
        auto it = prototypeOf.find(inst.object);
        if (it == prototypeOf.end()) {
            const ObjectDesc *obj = FindObject(desc, inst.object);
            if (!obj) throw SceneError(inst.loc, "unknown object " + Quote(inst.object));
            AccelOptions ao;
            ao.precision = settings.precision;
            ao.robust = settings.robust;
            ao.quality = settings.bvhQuality;
            auto proto = std::make_shared<Accel>(ao);
            std::vector<ShapeInfo> infos;
            for (const ShapeDesc &s : obj->shapes) {
                if (s.areaLight >= 0)
                    diag.Warn(s.loc,
                              "area lights inside object instances are not supported (as in "
                              "pbrt-v3); the shape does not emit");
                Transform instFromObject;
                std::optional<AnimatedTransform> motion = ShutterMotion(
                    ctx, nullptr, s.worldFromObject, s.motion, s.loc, &instFromObject);
                AddShapeTo(*proto, infos, s, instFromObject, motion);
            }
            // The prototype's BVH, once however many instances use it (the fixed part of the
            // estimate is charged once, with the top level).
            budget.Charge(
                EstimateBvhBytes(proto->NumTriangles(), UserPrimsOf(*proto)) - kBvhFixedBytes,
                "BVH", obj->loc);
            proto->Commit();
            scene.prototypes.push_back(std::move(infos));
            it = prototypeOf
                     .emplace(inst.object, std::make_pair(proto, int(scene.prototypes.size()) - 1))
                     .first;
        }
        if (it->second.first->NumShapes() == 0) return;
        Transform renderFromInstance;
        std::optional<AnimatedTransform> motion =
            ShutterMotion(ctx, &scene.renderFromWorld, inst.worldFromInstance, inst.motion,
                          inst.loc, &renderFromInstance);
        int index = motion ? scene.accel->AddInstance(it->second.first, *motion)
                           : scene.accel->AddInstance(it->second.first, renderFromInstance);
        if (int(scene.shapes.size()) <= index) scene.shapes.resize(size_t(index) + 1);
        ShapeInfo info;
        info.type = "instance";
        info.prototype = it->second.second;
        info.instance = int(&inst - desc.instances.data());
        scene.shapes[size_t(index)] = info;
        scene.features.effects.Enable(Effect::Instancing, "ObjectInstance " + Quote(inst.object),
                                      inst.loc);
    }

    void Build() {
        AccelOptions ao;
        ao.precision = settings.precision;
        ao.robust = settings.robust;
        ao.quality = settings.bvhQuality;
        const Bounds2i &pb = scene.pixelBounds;
        ao.expectedSamples = uint64_t(std::max(0, pb.pMax.x - pb.pMin.x)) *
                             uint64_t(std::max(0, pb.pMax.y - pb.pMin.y)) *
                             uint64_t(scene.sampler.spp);
        scene.accel = std::make_unique<Accel>(ao);
        for (const ShapeDesc &s : desc.shapes) AddShape(s);
        for (const InstanceDesc &inst : desc.instances) AddInstance(inst);
        for (const CsgDesc &node : desc.csg) AddCsg(node);
        for (const AreaLightDesc *a : usedAreaLights) a->params.ReportUnused(diag, "area light");
        if (!settings.buildBvh) return;
        // Meshes and analytic shapes, each instance as one user primitive.
        budget.Charge(EstimateBvhBytes(scene.accel->NumTriangles(), UserPrimsOf(*scene.accel)),
                      "BVH", desc.sourceFile.empty() ? FileLoc{} : FileLoc{desc.sourceFile, 0, 0});
        auto start = std::chrono::steady_clock::now();
        scene.accel->Commit();
        scene.buildSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
};

}  // namespace

void BuildShapesAndInstances(BuildContext &ctx, MaterialBuilder &materials) {
    ShapeBuilder(ctx, materials).Build();
}

}  // namespace prism
