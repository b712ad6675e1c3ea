#include "render/aov.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "image/film.h"
#include "render/bsdf.h"
#include "render/integrator.h"
#include "render/render_scene.h"
#include "render/sampler.h"

namespace prism {

namespace {

constexpr const char *Names[] = {
    "depth",        "P",           "N",           "Ng",     "albedo",   "uv",      "shape_id",
    "primitive_id", "instance_id", "material_id", "direct", "indirect", "variance"};
static_assert(sizeof(Names) / sizeof(Names[0]) == size_t(Aov::Count));

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

bool AovsNeedDirect(const std::vector<Aov> &aovs) {
    return std::find(aovs.begin(), aovs.end(), Aov::Direct) != aovs.end() ||
           std::find(aovs.begin(), aovs.end(), Aov::Indirect) != aovs.end();
}

AovFrame::AovFrame(const RenderScene &scene, const std::vector<Aov> &aovs, AovIdFn ids)
    : scene_(scene), aovs_(aovs), ids_(std::move(ids)), pb_(scene.pixelBounds) {
    auto has = [&](Aov a) { return std::find(aovs.begin(), aovs.end(), a) != aovs.end(); };
    const size_t nPixels = size_t(pb_.pMax.x - pb_.pMin.x) * size_t(pb_.pMax.y - pb_.pMin.y);
    std::fill(std::begin(slot_), std::end(slot_), -1);
    for (Aov a : aovs) {
        slot_[size_t(a)] = int(layers_.size());
        AovLayer l{a, AovChannels(a), {}};
        l.pixels.assign(nPixels * l.channels.size(), 0.f);
        layers_.push_back(std::move(l));
    }
    split_ = AovsNeedDirect(aovs);
    variance_ = has(Aov::Variance);
    albedo_ = has(Aov::Albedo);
    geometric_ = std::any_of(aovs.begin(), aovs.end(), [](Aov a) {
        return a != Aov::Variance && a != Aov::Direct && a != Aov::Indirect;
    });
    if (variance_) {
        mean_.assign(nPixels * 3, 0.0);
        m2_.assign(nPixels * 3, 0.0);
    }
    if (split_) {
        directSum_.assign(nPixels * 3, 0.0);
        indirectSum_.assign(nPixels * 3, 0.0);
    }
}

AovFrame::~AovFrame() = default;

float &AovFrame::At(Aov a, int x, int y, size_t c) {
    AovLayer &l = layers_[size_t(slot_[size_t(a)])];
    return l.pixels[(size_t(y - pb_.pMin.y) * size_t(pb_.pMax.x - pb_.pMin.x) +
                     size_t(x - pb_.pMin.x)) *
                        l.channels.size() +
                    c];
}

void AovFrame::BeginPass(int nTiles) {
    if (!split_) return;
    directFilm_ = std::make_unique<Film>(scene_.resolution, pb_, scene_.filter);
    indirectFilm_ = std::make_unique<Film>(scene_.resolution, pb_, scene_.filter);
    directTiles_.assign(size_t(nTiles), FilmTile{});
    indirectTiles_.assign(size_t(nTiles), FilmTile{});
}

void AovFrame::AddTile(const TileContext &ctx, int t, const TileSamples &samples) {
    const Bounds2i &tb = samples.bounds;
    const uint32_t spp = samples.spp;
    if (variance_) {
        // The tile's per-pixel mean and squared deviations (Welford), merged into what the
        // earlier passes left (Chan et al.).
        for (int y = tb.pMin.y; y < tb.pMax.y; ++y)
            for (int x = tb.pMin.x; x < tb.pMax.x; ++x) {
                double mean[3] = {0, 0, 0}, m2[3] = {0, 0, 0};
                for (uint32_t s = 0; s < spp; ++s) {
                    const RGB &L = samples.L[samples.Index(x, y, s)];
                    const float v[3] = {L.r, L.g, L.b};
                    for (int c = 0; c < 3; ++c) {
                        double d = double(v[c]) - mean[c];
                        mean[c] += d / double(s + 1);
                        m2[c] += d * (double(v[c]) - mean[c]);
                    }
                }
                const size_t p = (size_t(y - pb_.pMin.y) * size_t(pb_.pMax.x - pb_.pMin.x) +
                                  size_t(x - pb_.pMin.x)) *
                                 3;
                const double na = double(samples_), nb = double(spp), n = na + nb;
                for (int c = 0; c < 3; ++c) {
                    const double d = mean[c] - mean_[p + size_t(c)];
                    mean_[p + size_t(c)] += d * nb / n;
                    m2_[p + size_t(c)] += m2[c] + d * d * na * nb / n;
                }
            }
    }
    if (split_) {
        FilmTile &dt = directTiles_[size_t(t)], &it = indirectTiles_[size_t(t)];
        dt = directFilm_->MakeTile(tb);
        it = indirectFilm_->MakeTile(tb);
        for (int y = tb.pMin.y; y < tb.pMax.y; ++y)
            for (int x = tb.pMin.x; x < tb.pMax.x; ++x)
                for (uint32_t s = 0; s < spp; ++s) {
                    const size_t i = samples.Index(x, y, s);
                    dt.AddSample(samples.pFilm[i], samples.direct[i]);
                    it.AddSample(samples.pFilm[i], samples.L[i] - samples.direct[i]);
                }
    }
    if (geometric_ && firstPass_) AddGeometry(ctx, tb);
}

void AovFrame::EndPass(int spp) {
    if (variance_) samples_ += uint64_t(spp);
    if (split_) {
        for (size_t t = 0; t < directTiles_.size(); ++t) {
            directFilm_->MergeTile(directTiles_[t]);
            indirectFilm_->MergeTile(indirectTiles_[t]);
        }
        for (auto [film, sum] : {std::pair{directFilm_.get(), &directSum_},
                                 std::pair{indirectFilm_.get(), &indirectSum_}}) {
            const Image img = film->ToImage();
            for (size_t i = 0; i < sum->size(); ++i)
                (*sum)[i] += double(spp) * double(img.pixels[i]);
        }
        splitSpp_ += spp;
        directTiles_.clear();
        indirectTiles_.clear();
    }
    firstPass_ = false;
}

std::vector<AovLayer> AovFrame::Layers() const {
    std::vector<AovLayer> layers = layers_;
    auto fill = [&](Aov a, auto value) {
        if (slot_[size_t(a)] < 0) return;
        std::vector<float> &px = layers[size_t(slot_[size_t(a)])].pixels;
        for (size_t i = 0; i < px.size(); ++i) px[i] = value(i);
    };
    fill(Aov::Variance,
         [&](size_t i) { return samples_ > 1 ? float(m2_[i] / double(samples_ - 1)) : 0.f; });
    if (splitSpp_ > 0) {
        fill(Aov::Direct, [&](size_t i) { return float(directSum_[i] / double(splitSpp_)); });
        fill(Aov::Indirect, [&](size_t i) { return float(indirectSum_[i] / double(splitSpp_)); });
    }
    return layers;
}

void AovFrame::AddGeometry(const TileContext &ctx, const Bounds2i &tb) {
    const RenderScene &scene = scene_;
    const CameraSampler &camera = ctx.camera;
    const uint32_t spp = camera.Spp();
    const Transform worldFromRender = scene.renderFromWorld.Inverse();
    const Transform &renderFromCamera = scene.camera->RenderFromCamera();
    const Vec3d eye = renderFromCamera.Point(Vec3d(0, 0, 0));
    const Vec3d axis = Normalize(renderFromCamera.Vector(Vec3d(0, 0, 1)));
    // The first surface a ray shades (through "none" materials, as the integrators do), with
    // uv and tangents on every top-level shape whatever its material reads.
    auto intersect = [&](const Ray &ray, SurfaceInteraction *si) {
        RawHit hit;
        if (!scene.accel->IntersectRaw(ray, &hit)) return false;
        *si = scene.accel->Interaction(ray, hit, NeedAll);
        return true;
    };
    auto firstHit = [&](Ray ray, SurfaceInteraction *si) {
        if (!intersect(ray, si)) return false;
        for (int pass = 0; scene.materials[size_t(scene.Info(*si).material)].IsPassThrough();
             ++pass) {
            if (pass >= MaxPassThrough) return false;
            ray = si->SpawnRay(ray.d, scene.offset);
            if (!intersect(ray, si)) return false;
        }
        return true;
    };
    for (int y = tb.pMin.y; y < tb.pMax.y; ++y)
        for (int x = tb.pMin.x; x < tb.pMax.x; ++x) {
            const CameraSampler::Seeds seeds = camera.PixelSeeds(x, y);
            // The sample nearest the pixel centre (the first of equals).
            uint32_t nearest = 0;
            float best = Infinity;
            RGB albedoSum;
            for (uint32_t s = 0; s < spp; ++s) {
                const CameraSample cs = camera.Sample(x, y, s, seeds);
                float dx = cs.pFilm.x - (float(x) + 0.5f), dy = cs.pFilm.y - (float(y) + 0.5f);
                if (dx * dx + dy * dy < best) {
                    best = dx * dx + dy * dy;
                    nearest = s;
                }
                SurfaceInteraction si;
                if (albedo_ && firstHit(camera.GenerateRay(cs), &si)) {
                    const Material &m = scene.materials[size_t(scene.Info(si).material)];
                    BSDF bsdf = m.GetBSDF(si, SurfaceTextureContext(si));
                    const Vec3f wo = bsdf.ToLocal(si.wo);
                    for (int part = 0; part < bsdf.NumParts(); ++part) {
                        const BxDFLobes &l = bsdf.Part(part);
                        // A coated diffuse base (coateddiffuse) is its material's diffuse colour.
                        const bool coated = l.layered.base == LayeredLobe::Base::Diffuse;
                        RGB a = coated ? l.layered.reflectance : l.kd;
                        // Hair and tabulated BSDFs have no diffuse colour: their albedo at wo.
                        if (l.hair.Active()) a += l.hair.Albedo(wo);
                        if (l.fourier.Active()) a += l.fourier.Albedo(wo);
                        if (l.disney.Active()) a += l.disney.DiffuseColour();
                        albedoSum += bsdf.Weight(part) * a;
                    }
                }
            }
            if (albedo_) {
                RGB a = albedoSum / float(spp);
                At(Aov::Albedo, x, y, 0) = a.r;
                At(Aov::Albedo, x, y, 1) = a.g;
                At(Aov::Albedo, x, y, 2) = a.b;
            }
            SurfaceInteraction si;
            const bool hit = firstHit(camera.GenerateRay(camera.Sample(x, y, nearest, seeds)), &si);
            auto put3 = [&](Aov a, const Vec3d &v) {
                if (slot_[size_t(a)] < 0) return;
                At(a, x, y, 0) = float(v.x);
                At(a, x, y, 1) = float(v.y);
                At(a, x, y, 2) = float(v.z);
            };
            auto put1 = [&](Aov a, float v) {
                if (slot_[size_t(a)] >= 0) At(a, x, y, 0) = v;
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
            if (slot_[size_t(Aov::UV)] >= 0) {
                At(Aov::UV, x, y, 0) = si.uv.x;
                At(Aov::UV, x, y, 1) = si.uv.y;
            }
            int shape = 0, material = 0, instance = 0;
            if (ids_) ids_(si, &shape, &material, &instance);
            put1(Aov::ShapeId, float(shape));
            put1(Aov::PrimitiveId, float(si.prim));
            put1(Aov::InstanceId, float(instance));
            put1(Aov::MaterialId, float(material));
        }
}

}  // namespace prism
