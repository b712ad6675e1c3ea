// `prism study` (tools/study/study.h): the settings each knob runs, the error measures, and that
// the error falls where it must (spp, maxdepth) and shows what it must (acne, rays saved).
#include "tools/study/study.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/shared.h"
#include "support/temp_dir.h"
#include "tools/study/study_report.h"

namespace prism {
namespace {

using namespace test;

SceneDescription Load(const std::string &path) {
    Diagnostics diag;
    return LoadScene(path, diag);
}

// The row of `knob` = `value`; fails the test when missing.
const StudyRow &Row(const std::vector<StudyRow> &rows, const std::string &knob,
                    const std::string &value) {
    for (const StudyRow &r : rows)
        if (r.knob == knob && r.value == value) return r;
    ADD_FAILURE() << "no row " << knob << "=" << value;
    static StudyRow none;
    return none;
}

TEST(StudyKnobs, NamesRoundTrip) {
    std::vector<StudyKnob> all = AllStudyKnobs();
    ASSERT_EQ(all.size(), 10u);
    for (StudyKnob k : all) EXPECT_EQ(ParseKnobName(KnobName(k)), k) << KnobName(k);
    EXPECT_EQ(ParseKnobName("bvh-quality"), StudyKnob::BvhQuality);
    EXPECT_EQ(ParseKnobName("light-samples"), StudyKnob::LightSamples);
    EXPECT_EQ(ParseKnobName("light-sampler"), StudyKnob::LightSampler);
    EXPECT_FALSE(ParseKnobName("all"));
    EXPECT_FALSE(ParseKnobName("SPP"));
}

TEST(StudyKnobs, SettingsOfEachKnob) {
    StudyOptions o;
    auto values = [&](StudyKnob k) {
        std::vector<std::string> v;
        for (const StudySetting &s : KnobSettings(k, o)) v.push_back(s.value);
        return v;
    };
    using V = std::vector<std::string>;
    EXPECT_EQ(values(StudyKnob::Spp), (V{"1", "2", "4", "8", "16", "32", "64", "128"}));
    o.referenceSpp = 1024;
    EXPECT_EQ(values(StudyKnob::Spp).back(), "256");
    EXPECT_EQ(values(StudyKnob::MaxDepth).size(), 16u);
    EXPECT_EQ(values(StudyKnob::Cutoff), (V{"0", "1e-4", "1e-3", "1e-2"}));
    EXPECT_EQ(values(StudyKnob::Precision), (V{"float", "double"}));
    EXPECT_EQ(values(StudyKnob::Offset),
              (V{"errorbounds", "epsilon-1e-4", "epsilon-1e-3", "none"}));
    EXPECT_EQ(values(StudyKnob::Tessellate), (V{"8", "16", "32", "64", "128"}));
    EXPECT_EQ(values(StudyKnob::Robust), (V{"off", "on"}));
    EXPECT_EQ(values(StudyKnob::BvhQuality), (V{"low", "medium", "high"}));
    EXPECT_EQ(values(StudyKnob::LightSamples), (V{"1", "2", "4", "8", "16"}));
    EXPECT_EQ(values(StudyKnob::LightSampler), (V{"uniform", "power", "bvh"}));

    // Each setting changes what it names in the build settings.
    BuildSettings s;
    KnobSettings(StudyKnob::Offset, o)[1].apply(s);
    EXPECT_EQ(s.offset.mode, OffsetMode::FixedEpsilon);
    EXPECT_FLOAT_EQ(s.offset.epsilon, 1e-4f);
    KnobSettings(StudyKnob::Offset, o)[3].apply(s);
    EXPECT_EQ(s.offset.mode, OffsetMode::None);
    KnobSettings(StudyKnob::Cutoff, o)[2].apply(s);
    EXPECT_FLOAT_EQ(s.rayCutoff, 1e-3f);
    KnobSettings(StudyKnob::Robust, o)[1].apply(s);
    EXPECT_TRUE(s.robust);
    KnobSettings(StudyKnob::BvhQuality, o)[2].apply(s);
    EXPECT_EQ(s.bvhQuality, BvhQuality::High);
    KnobSettings(StudyKnob::Precision, o)[0].apply(s);
    EXPECT_EQ(s.precision, Precision::Float);
    KnobSettings(StudyKnob::Tessellate, o)[0].apply(s);
    EXPECT_TRUE(bool(s.replaceAnalyticShape));
    KnobSettings(StudyKnob::LightSamples, o)[3].apply(s);
    EXPECT_EQ(s.lightSamples, 8);
    KnobSettings(StudyKnob::LightSampler, o)[1].apply(s);
    EXPECT_EQ(s.lightSampler, "power");
}

TEST(StudyError, Measures) {
    Image ref(2, 1), img(2, 1);
    ref.SetRGB(0, 0, RGB(1, 1, 1));
    ref.SetRGB(1, 0, RGB(1, 1, 1));
    img.SetRGB(0, 0, RGB(1, 1, 1));
    img.SetRGB(1, 0, RGB(1.5f, 1, 1));  // one component off by 0.5
    ImageError e = MeasureError(img, ref, 0);
    EXPECT_DOUBLE_EQ(e.rmse, std::sqrt(0.25 / 6));
    EXPECT_DOUBLE_EQ(e.relL1, 0.5 / 6);
    EXPECT_DOUBLE_EQ(e.maxAbs, 0.5);
    EXPECT_NEAR(e.psnr, 10 * std::log10(6 / 0.25), 1e-12);
    EXPECT_EQ(e.badPixels, 1);
    EXPECT_EQ(e.nanCount, 0u);
    EXPECT_DOUBLE_EQ(e.relRmse, std::sqrt(0.25 / 6));  // the reference's rms is 1

    ImageError same = MeasureError(ref, ref, 3);
    EXPECT_EQ(same.rmse, 0);
    EXPECT_TRUE(std::isinf(same.psnr));
    EXPECT_EQ(same.badPixels, 0);
    EXPECT_EQ(same.nanCount, 3u);  // the renderer's NaN samples count

    img.SetRGB(1, 0, RGB(NAN, 1, 1));
    ImageError nan = MeasureError(img, ref, 0);
    EXPECT_EQ(nan.nanCount, 1u);
    EXPECT_EQ(nan.rmse, 0);  // the NaN component is left out of the other measures
    EXPECT_THROW(MeasureError(Image(3, 1), ref, 0), std::invalid_argument);
}

// A study of a tiny scene over every knob runs in seconds; one row per applicable setting, and
// the rows whose value is the base settings' render the base image.
TEST(Study, TinySceneAllKnobs) {
    SceneDescription desc = Load(Source + "/scenes/whitted.pbrt");
    StudyOptions o;
    o.resolution = {32, 24};
    o.repeats = 1;
    o.referenceSpp = 16;
    Diagnostics diag;
    int calls = 0, count = 0;
    StudyResult r = RunStudy(desc, "whitted", o, diag, [&](int i, int n, const StudySetting &) {
        EXPECT_EQ(i, ++calls);
        count = n;
    });
    // spp 1..8, maxdepth 1..16, cutoff 4, precision 2, offset 4, tessellate 5, robust 2, bvh 3,
    // light-samples 5 (the sky is an infinite light); light-sampler skipped (Whitted samples
    // every light).
    EXPECT_EQ(r.rows.size(), 4u + 16 + 4 + 2 + 4 + 5 + 2 + 3 + 5);
    EXPECT_EQ(count, int(r.rows.size()));
    EXPECT_EQ(calls, count);
    ASSERT_EQ(r.skipped.size(), 1u);
    EXPECT_EQ(r.skipped[0].knob, StudyKnob::LightSampler);
    EXPECT_NE(r.skipped[0].reason.find("whitted integrator"), std::string::npos);
    EXPECT_EQ(r.resolution, Vec2i(32, 24));
    EXPECT_EQ(r.baseSpp, 4);
    EXPECT_EQ(r.baseMaxDepth, 6);
    EXPECT_EQ(r.referenceMaxDepth, 16);

    const StudyRow &base = Row(r.rows, "spp", "4");
    EXPECT_TRUE(base.base);
    int baseRows = 0;
    for (const StudyRow &row : r.rows) {
        EXPECT_GT(row.rays, 0u) << row.knob << "=" << row.value;
        EXPECT_GT(row.timeSeconds, 0) << row.knob << "=" << row.value;
        EXPECT_GE(row.buildSeconds, 0);
        EXPECT_EQ(row.error.nanCount, 0u);
        if (!row.base) continue;
        ++baseRows;
        // Same image, same rays, whether re-rendered or rebuilt (the cutoff 0 image is the
        // image without a cutoff).
        EXPECT_EQ(row.error.rmse, base.error.rmse) << row.knob << "=" << row.value;
        EXPECT_EQ(row.rays, base.rays) << row.knob << "=" << row.value;
    }
    EXPECT_EQ(baseRows, 6);  // spp 4, maxdepth 6, cutoff 0, double, error bounds, ROBUST off

    // results.csv: the exact header and 11 fields a row.
    std::string csv = StudyCsv(r.rows);
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);
    EXPECT_EQ(line,
              "knob,value,time_s,build_s,rays,rmse,rel_l1,max_abs_err,psnr,bad_pixels,nan_count");
    size_t n = 0;
    while (std::getline(lines, line)) {
        EXPECT_EQ(std::count(line.begin(), line.end(), ','), 10) << line;
        ++n;
    }
    EXPECT_EQ(n, r.rows.size());
}

// The error falls with spp: not at every step (noise), but 64 spp is well below 1 spp.
TEST(Study, ErrorFallsWithSpp) {
    SceneDescription desc = Load(Source + "/scenes/whitted.pbrt");
    StudyOptions o;
    o.knobs = {StudyKnob::Spp};
    o.resolution = {40, 30};
    o.repeats = 1;
    o.referenceSpp = 128;
    Diagnostics diag;
    StudyResult r = RunStudy(desc, "whitted", o, diag);
    ASSERT_EQ(r.rows.size(), 7u);  // 1 .. 64
    double e1 = Row(r.rows, "spp", "1").error.rmse, e64 = Row(r.rows, "spp", "64").error.rmse;
    EXPECT_LT(e64, 0.5 * e1);
    EXPECT_GT(Row(r.rows, "spp", "1").error.badPixels, Row(r.rows, "spp", "64").error.badPixels);
    EXPECT_LT(Row(r.rows, "spp", "1").rays, Row(r.rows, "spp", "64").rays);
}

// Between two facing mirrors each bounce adds a dimmer copy of the sphere: the error falls
// with maxdepth and vanishes at the reference's depth (the base spp is the reference's here).
TEST(Study, ErrorFallsWithMaxDepthBetweenMirrors) {
    SceneDescription desc = Load(Source + "/scenes/mirrors.pbrt");
    StudyOptions o;
    o.knobs = {StudyKnob::MaxDepth};
    o.resolution = {48, 36};
    o.repeats = 1;
    o.referenceSpp = 4;
    o.baseSpp = 4;
    Diagnostics diag;
    StudyResult r = RunStudy(desc, "mirrors", o, diag);
    ASSERT_EQ(r.rows.size(), 16u);
    auto rmse = [&](int d) { return Row(r.rows, "maxdepth", std::to_string(d)).error.rmse; };
    EXPECT_GT(rmse(1), rmse(2));
    EXPECT_GT(rmse(2), rmse(4));
    EXPECT_GT(rmse(4), rmse(8));
    EXPECT_GT(rmse(1), 10 * rmse(8));
    EXPECT_EQ(rmse(16), 0);
    EXPECT_GT(Row(r.rows, "maxdepth", "1").error.badPixels, 0);
}

TEST(Study, SkipsKnobsThatDoNotApply) {
    // One matte triangle under a point light: no analytic shapes, no specular material, no
    // area or infinite light.
    std::filesystem::path dir = test::ScratchDir("study_skip");
    std::string path = test::WriteTestFile(dir / "flat.pbrt", R"(
LookAt 0 0 -3  0 0 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
Film "image" "integer xresolution" [ 16 ] "integer yresolution" [ 12 ]
WorldBegin
LightSource "point" "point3 from" [ 0 0 -3 ] "rgb I" [ 5 5 5 ]
Material "matte"
Shape "trianglemesh" "integer indices" [ 0 1 2 ] "point3 P" [ -1 -1 0  1 -1 0  0 1 0 ]
WorldEnd
)");
    SceneDescription desc = Load(path);
    StudyOptions o;
    o.repeats = 1;
    o.referenceSpp = 4;
    Diagnostics diag;
    StudyResult r = RunStudy(desc, "flat", o, diag);
    std::map<std::string, std::string> skipped;
    for (const SkippedKnob &s : r.skipped) skipped[KnobName(s.knob)] = s.reason;
    EXPECT_EQ(skipped.size(), 5u);
    EXPECT_NE(skipped["maxdepth"].find("specular"), std::string::npos);
    EXPECT_NE(skipped["precision"].find("analytic"), std::string::npos);
    EXPECT_NE(skipped["tessellate"].find("analytic"), std::string::npos);
    EXPECT_NE(skipped["light-samples"].find("area or infinite"), std::string::npos);
    EXPECT_NE(skipped["light-sampler"].find("one light"), std::string::npos);
    for (const StudyRow &row : r.rows) EXPECT_EQ(skipped.count(row.knob), 0u) << row.knob;
    // spp 1, 2 (below the reference's 4), cutoff 4, offset 4, robust 2, bvh-quality 3.
    EXPECT_EQ(r.rows.size(), 2u + 4 + 4 + 2 + 3);
    std::string report = StudyReport(r);
    EXPECT_NE(report.find("## Knobs not studied"), std::string::npos);
    EXPECT_NE(report.find("- `maxdepth`: "), std::string::npos);
}

// On a floor that is a sphere of radius 1e5, a fixed offset of 1e-4 leaves acne, the
// error-bound offset none (the base spp is the reference's, so only the offset differs).
TEST(Study, FixedEpsilonGivesAcneOnHugeSphere) {
    SceneDescription desc = Load(Source + "/tests/tools/study/huge_floor.pbrt");
    StudyOptions o;
    o.knobs = {StudyKnob::Offset};
    o.repeats = 1;
    o.referenceSpp = 1;
    o.baseSpp = 1;
    Diagnostics diag;
    StudyResult r = RunStudy(desc, "huge_floor", o, diag);
    ASSERT_EQ(r.rows.size(), 4u);
    const StudyRow &bounds = Row(r.rows, "offset", "errorbounds");
    const StudyRow &eps = Row(r.rows, "offset", "epsilon-1e-4");
    const StudyRow &none = Row(r.rows, "offset", "none");
    EXPECT_EQ(bounds.error.badPixels, 0);
    EXPECT_EQ(bounds.error.rmse, 0);
    EXPECT_GT(eps.error.badPixels, 0);
    EXPECT_GT(none.error.badPixels, 0);
}

// A ray-weight cutoff of 1e-2 traces fewer rays than none, for a small error.
TEST(Study, CutoffSavesRays) {
    SceneDescription desc = Load(Source + "/scenes/whitted.pbrt");
    StudyOptions o;
    o.knobs = {StudyKnob::Cutoff};
    o.resolution = {32, 24};
    o.repeats = 1;
    o.referenceSpp = 4;
    o.baseSpp = 4;
    Diagnostics diag;
    StudyResult r = RunStudy(desc, "whitted", o, diag);
    const StudyRow &none = Row(r.rows, "cutoff", "0"), &cut = Row(r.rows, "cutoff", "1e-2");
    EXPECT_LT(cut.rays, none.rays);
    EXPECT_GE(cut.error.rmse, none.error.rmse);
    EXPECT_LT(cut.error.rmse, 0.05);
}

}  // namespace
}  // namespace prism
