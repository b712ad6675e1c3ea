// The orchestrator: each step reads its directives' pbrt parameters (pbrt-v3 names and
// defaults) and fills its part of the RenderScene.
#include "assembly/build_scene.h"

#include "assembly/camera_film.h"
#include "assembly/lights.h"
#include "assembly/materials.h"
#include "assembly/media.h"
#include "assembly/scene_effects.h"
#include "assembly/shapes.h"
#include "assembly/textures.h"
#include "render/light_sampling.h"

namespace prism {

RenderScene BuildRenderScene(const SceneDescription &desc, const BuildSettings &settings,
                             Diagnostics &diag) {
    RenderScene scene;
    MemoryBudget ownBudget;  // the default limit, when the caller passes no budget
    MemoryBudget &budget = settings.budget ? *settings.budget : ownBudget;
    // Option "disabletexturefiltering" is --texture-filter point unless the caller chose.
    const SceneOptions options = ReadSceneOptions(desc, diag);
    BuildSettings optioned;
    const bool pointLookups = options.disableTextureFiltering && settings.textureFilter.empty();
    if (pointLookups) {
        optioned = settings;
        optioned.textureFilter = "point";
    }
    BuildContext ctx{desc, pointLookups ? optioned : settings, diag, scene, budget, {}, {}, {}};
    ctx.options = options;
    BuildFilm(ctx);
    BuildCamera(ctx);  // sets renderFromWorld, which every later step uses
    BuildIntegratorSettings(ctx);
    BuildSampler(ctx);  // after the integrator: whether it draws pbrt's sample patterns
    BuildPixelFilter(ctx);
    ChargeFilmMemory(ctx);  // needs the crop window and the filter's radius
    BuildTextures(ctx);
    BuildLights(ctx);
    BuildMedia(ctx);
    MaterialBuilder materials(ctx);  // created on demand, as shapes use them
    BuildShapesAndInstances(ctx, materials);
    WarnIgnoredMedia(ctx);
    FinishEffects(ctx);
    ComputeLightPower(scene);  // the path and directlighting integrators' light choice
    // Rays carry differentials only where a texture filters over their footprint.
    for (const Material &m : scene.materials) {
        scene.differentials |= m.UsesDifferentials();
        scene.passThrough |= m.IsPassThrough();
    }
    scene.allEffects = settings.allEffects;
    scene.estimateNoise = settings.estimateNoise;
    scene.integrator->Prepare(scene);  // the lights exist: e.g. the light choice
    scene.memoryLimit = budget.Limit();
    scene.memoryCommitted = budget.Used();
    if (scene.lights.empty())
        diag.Warn(desc.sourceFile.empty() ? FileLoc{} : FileLoc{desc.sourceFile, 0, 0},
                  "the scene has no light sources");
    return scene;
}

}  // namespace prism
