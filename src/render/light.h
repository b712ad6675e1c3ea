// Light sources (pbrt-v3 lights/*.cpp): point, spot and distant. Each gives, for a shading
// point, the incident radiance along a direction and the point the shadow ray must reach.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/params.h"
#include "core/transform.h"
#include "geometry/interaction.h"
#include "render/light_bounds.h"

namespace prism {

struct Image;

struct LightSample {
    RGB Li;
    Vec3f wi;               // unit direction toward the light
    Vec3f pLight;           // for finite lights: the point to reach
    bool infinite = false;  // distant/infinite: the shadow ray is unbounded along wi
    float pdf = 1;
    Vec3f n;       // area lights: the unit surface normal at pLight (zero for the others)
    int prim = 0;  // mesh area lights: the triangle of pLight
};

// The first step of SampleLi at a light that is a point at pos (point, spot, goniometric and
// projection lights): ls's direction from si toward pos and the delta sample's fields, and
// the squared distance; false when si is at pos. The caller sets ls->Li.
bool SamplePointPosition(const Vec3f &pos, const SurfaceInteraction &si, LightSample *ls,
                         float *dist2);

// The sphere that bounds the scene, where distant and infinite lights start the rays they emit.
struct SceneSphere {
    Vec3f center;
    float radius = 1;
};

// A ray leaving a light (light tracing: the bidirectional integrator's light subpaths),
// pbrt-v3's Light::Sample_Le.
struct LightLeSample {
    Ray ray;       // from the light (distant and infinite: from a disk outside the scene)
    Vec3f n;       // the unit surface normal at ray.o (area lights; zero for the others)
    RGB Le;        // the radiance (point and spot: intensity) along the ray
    float pdfPos;  // the origin's density: per unit area (1 for point and spot lights)
    float pdfDir;  // the direction's, per unit solid angle (1 for distant lights)
};

class Light {
  public:
    virtual ~Light() = default;
    virtual const char *Name() const = 0;
    // u: a 2-D sample in [0,1)^2 (ignored by delta lights).
    virtual bool SampleLi(const SurfaceInteraction &si, Vec2f u, LightSample *ls) const = 0;
    // Radiance seen along an escaping ray (infinite lights only).
    virtual RGB Le(const Ray &) const { return RGB(0); }
    virtual int NumSamples() const { return 1; }
    virtual bool IsArea() const { return false; }
    // False for delta lights, whose SampleLi ignores u: the integrator then skips computing it.
    virtual bool UsesSample() const { return true; }
    // Point, spot and distant lights: no ray can hit them (no multiple importance sampling).
    bool IsDelta() const { return !UsesSample(); }
    // The solid-angle density with which SampleLi(ref, ...) gives direction wi (multiple
    // importance sampling of the path and directlighting integrators); `hit` is where a ray
    // along wi met this light's surface (area lights), null for an escaping ray. 0 for delta
    // lights.
    virtual float PdfLi(const SurfaceInteraction &ref, const Vec3f &wi,
                        const SurfaceInteraction *hit) const {
        return 0;
    }
    // The emitted power's luminance (pbrt-v3 Light::Power().y()), for choosing lights in
    // proportion to it; sceneRadius bounds the scene (distant and infinite lights).
    virtual double Power(double sceneRadius) const = 0;

    // Light tracing (pbrt-v3 Sample_Le and Pdf_Le). SampleLe draws an emitted ray from two
    // samples in [0,1)^2 (uPos: the origin, uDir: the direction; infinite lights draw their
    // direction from uDir and the disk point from uPos). PdfLe gives the densities SampleLe
    // draws a ray from p with unit normal n (area lights) in direction w with; distant and
    // infinite lights read only w (their pdfPos is the disk's).
    virtual bool SampleLe(Vec2f uPos, Vec2f uDir, const SceneSphere &sphere,
                          LightLeSample *ls) const = 0;
    virtual void PdfLe(const Vec3f &p, const Vec3f &n, const Vec3f &w, const SceneSphere &sphere,
                       float *pdfPos, float *pdfDir) const = 0;
    // Distant and infinite lights: light arriving from infinitely far along a direction.
    virtual bool IsInfinite() const { return false; }
    // What the light emits where, for the light BVH (render/light_bvh.h): one entry per part
    // the BVH may choose alone (an emissive mesh: each triangle it samples; the others: the
    // light whole, prim -1). None for lights from infinitely far, which the BVH chooses apart.
    virtual void Bounds(std::vector<LightPartBounds> *) const {}
};

class PointLight final : public Light {
  public:
    PointLight(const Vec3f &pos, const RGB &I) : pos_(pos), I_(I) {}
    const char *Name() const override { return "point"; }
    bool UsesSample() const override { return false; }
    bool SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const override;
    double Power(double) const override { return 4 * Pi * I_.Luminance(); }
    void Bounds(std::vector<LightPartBounds> *parts) const override;
    bool SampleLe(Vec2f uPos, Vec2f uDir, const SceneSphere &sphere,
                  LightLeSample *ls) const override;
    void PdfLe(const Vec3f &p, const Vec3f &n, const Vec3f &w, const SceneSphere &sphere,
               float *pdfPos, float *pdfDir) const override;

  private:
    Vec3f pos_;
    RGB I_;
};

class SpotLight final : public Light {
  public:
    // The curve between the cone's full-intensity core and its edge.
    enum class FalloffCurve { Quartic, SmoothStep };  // pbrt-v3's, pbrt-v4's
    // dir: unit axis from the light toward `to`; angles in degrees.
    SpotLight(const Vec3f &pos, const Vec3f &dir, const RGB &I, float coneAngle, float coneDelta,
              FalloffCurve curve = FalloffCurve::Quartic);
    const char *Name() const override { return "spot"; }
    bool UsesSample() const override { return false; }
    bool SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const override;
    float Falloff(const Vec3f &wFromLight) const;
    double Power(double) const override {
        return 2 * Pi * I_.Luminance() * (1 - 0.5 * (cosFalloffStart_ + cosTotalWidth_));
    }
    void Bounds(std::vector<LightPartBounds> *parts) const override;
    bool SampleLe(Vec2f uPos, Vec2f uDir, const SceneSphere &sphere,
                  LightLeSample *ls) const override;
    void PdfLe(const Vec3f &p, const Vec3f &n, const Vec3f &w, const SceneSphere &sphere,
               float *pdfPos, float *pdfDir) const override;

  private:
    Vec3f pos_, dir_;
    RGB I_;
    float cosTotalWidth_, cosFalloffStart_;
    FalloffCurve curve_;
};

class DistantLight final : public Light {
  public:
    // wLight: unit direction *toward* the light (from - to).
    DistantLight(const Vec3f &wLight, const RGB &L) : w_(wLight), L_(L) {}
    const char *Name() const override { return "distant"; }
    bool UsesSample() const override { return false; }
    bool SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const override;
    double Power(double r) const override { return Pi * r * r * L_.Luminance(); }
    bool SampleLe(Vec2f uPos, Vec2f uDir, const SceneSphere &sphere,
                  LightLeSample *ls) const override;
    void PdfLe(const Vec3f &p, const Vec3f &n, const Vec3f &w, const SceneSphere &sphere,
               float *pdfPos, float *pdfDir) const override;
    bool IsInfinite() const override { return true; }

  private:
    Vec3f w_;
    RGB L_;
};

// The bounds of a light at the point pos emitting phi within the cone (w, theta_o), along the
// cone's directions (cosTheta_e 1) or from any direction (0) of it.
LightPartBounds PointBounds(const Vec3f &pos, float phi, const Vec3f &w, float cosTheta_o,
                            float cosTheta_e);

// Light tracing's shared steps: a uniform direction on the unit sphere and in a cone about z
// (cosMax: the cone's half angle), a concentric point on the unit disk, and the origin of a ray
// entering the scene sphere in direction d through the disk sample u (density 1 / (pi r^2)).
Vec3f UniformSphereDirection(Vec2f u);
Vec3f UniformConeDirection(Vec2f u, float cosMax);
Vec2f ConcentricDisk(Vec2f u);
Vec3f DiskOrigin(const SceneSphere &sphere, const Vec3f &d, Vec2f u);

// A LightSource directive's parameters as a light's Create reads them: core/params.h's plus
// spectra (rgb, blackbody, spectrum: as RGB), points, and images (relative to the scene).
class LightParams : public Params {
  public:
    // Spectrum parameter `name`. In a pbrt-v4 file, an emission spectrum ("I", "L") that is
    // not RGB (a blackbody, a named illuminant, samples) comes normalised to luminance 1, as
    // pbrt-v4 divides a light's spectrum by its photometric value.
    virtual RGB Spectrum(const char *name, RGB def) const = 0;
    virtual Vec3f Point3(const char *name, Vec3f def) const = 0;
    virtual std::vector<Vec3f> Point3s(const char *name) const = 0;  // empty when absent
    // pbrt's "scale": a float or a spectrum, 1 by default.
    virtual RGB Scale() const = 0;
    // The image file named by string parameter `name` (relative to the scene), linear.
    virtual std::shared_ptr<const Image> LoadImage(const char *name,
                                                   const std::string &file) const = 0;
    // The image named by string parameter `name`, or null when the parameter is absent or "".
    std::shared_ptr<const Image> OptionalImage(const char *name) const {
        const std::string file = String(name, "");
        return file.empty() ? nullptr : LoadImage(name, file);
    }
};

// pbrt-v4's photometric parameters ("power" of point, spot and area lights, "illuminance" of
// distant and infinite lights): the spectrum `value` (already times "scale") multiplied by
// `param`'s value over k_e, the power or illuminance the light has per unit of it. pbrt-v4
// measures an RGB spectrum by its colour space's white, so an RGB value keeps its magnitude
// (measured with pbrt-v4: "rgb I" [2 2 2] at "power" 100 is twice as bright as [1 1 1]); any
// other spectrum (a blackbody) counts as luminance 1, which in a pbrt-v4 file it already is
// (LightParams::Spectrum normalises it). The value unchanged without `param`; SceneError for a
// negative or non-finite one.
RGB PhotometricScale(const LightParams &p, const RGB &value, const char *param, double k_e,
                     const FileLoc &loc);

// A light's map over the sphere of directions: pbrt-v3's "mapname" (latitude-longitude) or
// pbrt-v4's "filename" (a square equal-area image, core/equal_area.h): the image (null
// without either) and which it is. SceneError at "filename" when both are given or its image
// is not square; `light` names the light in messages ("infinite light").
struct SphereMap {
    std::shared_ptr<const Image> image;
    bool equalArea = false;
};
SphereMap ReadSphereMap(const LightParams &p, const char *light);

// What a light's Create reads.
struct LightInputs {
    const LightParams &params;
    Transform renderFromLight;  // the CTM at the LightSource, in render space
    FileLoc loc;                // the directive
    int lightSamples = 0;       // --light-samples (0: the file's "nsamples")
    int pbrtVersion = 3;        // the pbrt rules the file is read by (scene/pbrt_version.h)
    Transform renderFromWorld;  // for what a light gives in world space (pbrt-v4's "portal")
};

// The light registered as `type` (light_list.inc), or null when none is. Throws SceneError for
// bad parameters.
std::unique_ptr<Light> CreateLight(const std::string &type, const LightInputs &in);
const std::vector<std::string> &LightNames();

}  // namespace prism
