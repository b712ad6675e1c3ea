#include "render/aov.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "image/film.h"
#include "render/bsdf.h"
#include "render/kernel.h"
#include "render/render_scene.h"
#include "render/sampler.h"

namespace prism {

namespace {

constexpr const char *Names[] = {
    "depth",        "P",           "N",           "Ng",     "albedo",   "uv",      "shape_id",
    "primitive_id", "instance_id", "material_id", "direct", "indirect", "variance"};
static_assert(sizeof(Names) / sizeof(Names[0]) == size_t(Aov::Count));

constexpr int BandRows = 8;

}  // namespace

const char *AovName(Aov a) { return Names[size_t(a)]; }

std::vector<std::string> AovChannels(Aov a) {
    auto xyz = [](const std::string &l) {
        return std::vector<std::string>{l + ".X", l + ".Y", l + ".Z"};
    };
    auto rgb = [](const std::string &l) {
        return std::vector<std::string>{l + ".R", l + ".G", l + ".B"};
    };
    switch (a) {
        case Aov::Depth:
            return {"Z"};
        case Aov::Position:
            return xyz("P");
        case Aov::Normal:
            return xyz("N");
        case Aov::GeoNormal:
            return xyz("Ng");
        case Aov::UV:
            return {"uv.U", "uv.V"};
        case Aov::Albedo:
        case Aov::Direct:
        case Aov::Indirect:
        case Aov::Variance:
            return rgb(AovName(a));
        default:
            return {AovName(a)};
    }
}

bool ParseAovList(const std::string &list, std::vector<Aov> *aovs, std::string *error) {
    bool want[size_t(Aov::Count)] = {};
    if (list == "all") {
        std::fill(std::begin(want), std::end(want), true);
    } else {
        size_t start = 0;
        while (start <= list.size()) {
            size_t end = std::min(list.find(',', start), list.size());
            std::string name = list.substr(start, end - start);
            size_t i = 0;
            while (i < size_t(Aov::Count) && name != Names[i]) ++i;
            if (i == size_t(Aov::Count)) {
                std::string known;
                for (const char *n : Names) known += std::string(known.empty() ? "" : ", ") + n;
                *error = "unknown AOV \"" + name + "\" (expected all or a list of " + known + ")";
                return false;
            }
            want[i] = true;
            start = end + 1;
        }
    }
    aovs->clear();
    for (size_t i = 0; i < size_t(Aov::Count); ++i)
        if (want[i]) aovs->push_back(Aov(i));
    return true;
}

bool AovsNeedWhitted(const std::vector<Aov> &aovs) {
    return std::find(aovs.begin(), aovs.end(), Aov::Direct) != aovs.end() ||
           std::find(aovs.begin(), aovs.end(), Aov::Indirect) != aovs.end();
}

std::vector<AovLayer> RenderAovs(const RenderScene &scene, const std::vector<Aov> &aovs,
                                 const AovIdFn &ids) {
    auto has = [&](Aov a) { return std::find(aovs.begin(), aovs.end(), a) != aovs.end(); };
    const Bounds2i pb = scene.pixelBounds;
    const int w = pb.pMax.x - pb.pMin.x, h = pb.pMax.y - pb.pMin.y;
    const size_t nPixels = size_t(w) * size_t(h);
    std::vector<AovLayer> layers;
    int slot[size_t(Aov::Count)];
    std::fill(std::begin(slot), std::end(slot), -1);
    for (Aov a : aovs) {
        slot[size_t(a)] = int(layers.size());
        AovLayer l{a, AovChannels(a), {}};
        l.pixels.assign(nPixels * l.channels.size(), 0.f);
        layers.push_back(std::move(l));
    }
    auto at = [&](Aov a, int x, int y, size_t c) -> float & {
        AovLayer &l = layers[size_t(slot[size_t(a)])];
        return l.pixels[(size_t(y - pb.pMin.y) * size_t(w) + size_t(x - pb.pMin.x)) *
                            l.channels.size() +
                        c];
    };

    const uint32_t spp = uint32_t(scene.spp);
    const CMJPattern cmj(spp);
    const bool lens = scene.features.lens;
    const bool motion = scene.features.effects.Has(Effect::MotionBlur);
    auto cameraRay = [&](int x, int y, uint32_t s, Vec2f *pFilm) {
        Vec2f u = spp == 1 ? Vec2f(0.5f, 0.5f) : cmj.Sample(s, PatternSeed(x, y, FilmPurpose));
        *pFilm = FilmPosition(x, y, u);
        Vec2f uLens = lens ? cmj.Sample(s, PatternSeed(x, y, LensPurpose)) : Vec2f(0.5f, 0.5f);
        float time = motion ? cmj.Sample(s, PatternSeed(x, y, TimePurpose)).x : 0.f;
        return scene.camera->GenerateRay(*pFilm, uLens, time);
    };
    const int bands = (h + BandRows - 1) / BandRows;
    auto bandBounds = [&](int b) {
        Bounds2i r = pb;
        r.pMin.y = pb.pMin.y + b * BandRows;
        r.pMax.y = std::min(pb.pMax.y, r.pMin.y + BandRows);
        return r;
    };

    // Pass 1, with the surface data the beauty computed: the beauty's samples again through the
    // general kernel (the same values, tests/render/kernel_test.cpp), for the variance, and
    // through the kernel without specular rays for the direct part.
    const bool variance = has(Aov::Variance), split = has(Aov::Direct) || has(Aov::Indirect);
    if (variance || split) {
        const bool glossyRays = scene.integrator == IntegratorKind::Distribution;
        const Kernel<KernelAll> full(scene, glossyRays);
        constexpr uint32_t DirectMask = KernelAll & ~(KernelSpecular | KernelGlossy);
        const Kernel<DirectMask> direct(scene, false);
        std::optional<Film> directFilm, indirectFilm;
        std::vector<FilmTile> directTiles(static_cast<size_t>(bands)),
            indirectTiles(static_cast<size_t>(bands));
        if (split) {
            directFilm.emplace(scene.resolution, pb, scene.filter);
            indirectFilm.emplace(scene.resolution, pb, scene.filter);
        }
        tbb::parallel_for(0, bands, [&](int b) {
            const Bounds2i bb = bandBounds(b);
            if (split) {
                directTiles[size_t(b)] = directFilm->MakeTile(bb);
                indirectTiles[size_t(b)] = indirectFilm->MakeTile(bb);
            }
            RayCounters rc;
            for (int y = bb.pMin.y; y < bb.pMax.y; ++y)
                for (int x = bb.pMin.x; x < bb.pMax.x; ++x) {
                    double mean[3] = {0, 0, 0}, m2[3] = {0, 0, 0};
                    for (uint32_t s = 0; s < spp; ++s) {
                        Vec2f pFilm;
                        Ray ray = cameraRay(x, y, s, &pFilm);
                        RawHit hit;
                        if (!scene.accel->IntersectRaw(ray, &hit)) hit.shape = -1;
                        SampleContext sc{x, y, s, spp};
                        RGB L = full.LiCamera(ray, hit, rc, sc) * scene.filmScale;
                        float clamp = 1;
                        if (scene.maxSampleLuminance < Infinity && L.IsFinite()) {
                            float lum = L.Luminance();
                            if (lum > scene.maxSampleLuminance)
                                clamp = scene.maxSampleLuminance / lum;
                        }
                        L *= clamp;
                        if (variance) {
                            const float v[3] = {L.r, L.g, L.b};
                            for (int c = 0; c < 3; ++c) {
                                double d = double(v[c]) - mean[c];
                                mean[c] += d / double(s + 1);
                                m2[c] += d * (double(v[c]) - mean[c]);
                            }
                        }
                        if (split) {
                            RGB D = direct.LiCamera(ray, hit, rc, sc) * (scene.filmScale * clamp);
                            directTiles[size_t(b)].AddSample(pFilm, D);
                            indirectTiles[size_t(b)].AddSample(pFilm, L - D);
                        }
                    }
                    if (variance)
                        for (int c = 0; c < 3; ++c)
                            at(Aov::Variance, x, y, size_t(c)) =
                                spp > 1 ? float(m2[c] / double(spp - 1)) : 0.f;
                }
        });
        if (split) {
            // Merged in band order: the sums do not depend on the threads.
            for (int b = 0; b < bands; ++b) {
                directFilm->MergeTile(directTiles[size_t(b)]);
                indirectFilm->MergeTile(indirectTiles[size_t(b)]);
            }
            for (auto [a, film] :
                 {std::pair{Aov::Direct, &*directFilm}, std::pair{Aov::Indirect, &*indirectFilm}}) {
                if (!has(a)) continue;
                Image img = film->ToImage();
                for (int y = pb.pMin.y; y < pb.pMax.y; ++y)
                    for (int x = pb.pMin.x; x < pb.pMax.x; ++x) {
                        RGB c = img.GetRGB(x - pb.pMin.x, y - pb.pMin.y);
                        at(a, x, y, 0) = c.r;
                        at(a, x, y, 1) = c.g;
                        at(a, x, y, 2) = c.b;
                    }
            }
        }
    }

    // Pass 2: the first hit of each sample with uv and tangents on every top-level shape.
    const bool geometric = std::any_of(aovs.begin(), aovs.end(), [](Aov a) {
        return a != Aov::Variance && a != Aov::Direct && a != Aov::Indirect;
    });
    if (!geometric) return layers;
    for (int i = 0; i < scene.accel->NumShapes(); ++i)
        if (scene.shapes[size_t(i)].prototype < 0) scene.accel->SetSurfaceNeeds(i, NeedAll);
    const Transform worldFromRender = scene.renderFromWorld.Inverse();
    const Transform &renderFromCamera = scene.camera->RenderFromCamera();
    const Vec3d eye = renderFromCamera.Point(Vec3d(0, 0, 0));
    const Vec3d axis = Normalize(renderFromCamera.Vector(Vec3d(0, 0, 1)));
    // The first surface a ray shades (through "none" materials, as the kernel does).
    auto firstHit = [&](Ray ray, SurfaceInteraction *si) {
        if (!scene.accel->Intersect(ray, si)) return false;
        for (int pass = 0; scene.materials[size_t(scene.Info(*si).material)].IsPassThrough();
             ++pass) {
            if (pass >= 256) return false;
            ray = si->SpawnRay(ray.d, scene.offset);
            if (!scene.accel->Intersect(ray, si)) return false;
        }
        return true;
    };
    const bool albedo = has(Aov::Albedo);
    tbb::parallel_for(0, bands, [&](int b) {
        const Bounds2i bb = bandBounds(b);
        for (int y = bb.pMin.y; y < bb.pMax.y; ++y)
            for (int x = bb.pMin.x; x < bb.pMax.x; ++x) {
                // The sample nearest the pixel centre (the first of equals).
                uint32_t nearest = 0;
                float best = Infinity;
                RGB albedoSum;
                for (uint32_t s = 0; s < spp; ++s) {
                    Vec2f pFilm;
                    Ray ray = cameraRay(x, y, s, &pFilm);
                    float dx = pFilm.x - (float(x) + 0.5f), dy = pFilm.y - (float(y) + 0.5f);
                    if (dx * dx + dy * dy < best) {
                        best = dx * dx + dy * dy;
                        nearest = s;
                    }
                    SurfaceInteraction si;
                    if (albedo && firstHit(ray, &si)) {
                        const Material &m = scene.materials[size_t(scene.Info(si).material)];
                        BSDF bsdf = m.GetBSDF(si, TextureContext{si.uv, si.p, si.uv1});
                        for (int part = 0; part < bsdf.NumParts(); ++part)
                            albedoSum += bsdf.Weight(part) * bsdf.Part(part).kd;
                    }
                }
                if (albedo) {
                    RGB a = albedoSum / float(spp);
                    at(Aov::Albedo, x, y, 0) = a.r;
                    at(Aov::Albedo, x, y, 1) = a.g;
                    at(Aov::Albedo, x, y, 2) = a.b;
                }
                Vec2f pFilm;
                Ray ray = cameraRay(x, y, nearest, &pFilm);
                SurfaceInteraction si;
                const bool hit = firstHit(ray, &si);
                auto put3 = [&](Aov a, const Vec3d &v) {
                    if (slot[size_t(a)] < 0) return;
                    at(a, x, y, 0) = float(v.x);
                    at(a, x, y, 1) = float(v.y);
                    at(a, x, y, 2) = float(v.z);
                };
                auto put1 = [&](Aov a, float v) {
                    if (slot[size_t(a)] >= 0) at(a, x, y, 0) = v;
                };
                if (!hit) {
                    put1(Aov::Depth, Infinity);
                    put1(Aov::PrimitiveId, -1.f);
                    continue;
                }
                const Vec3d p(si.p);
                put1(Aov::Depth, float(Dot(p - eye, axis)));
                put3(Aov::Position, worldFromRender.Point(p));
                put3(Aov::Normal, Normalize(worldFromRender.Normal(Vec3d(si.ns))));
                put3(Aov::GeoNormal, Normalize(worldFromRender.Normal(Vec3d(si.n))));
                if (slot[size_t(Aov::UV)] >= 0) {
                    at(Aov::UV, x, y, 0) = si.uv.x;
                    at(Aov::UV, x, y, 1) = si.uv.y;
                }
                int shape = 0, material = 0, instance = 0;
                if (ids) ids(si, &shape, &material, &instance);
                put1(Aov::ShapeId, float(shape));
                put1(Aov::PrimitiveId, float(si.prim));
                put1(Aov::InstanceId, float(instance));
                put1(Aov::MaterialId, float(material));
            }
    });
    return layers;
}

}  // namespace prism
