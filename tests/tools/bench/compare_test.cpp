// prism bench compare: the ladder, the pbrt-v3 sample-count rewrite, the log-log fit and the
// last line; and the command end to end with fake reference renderers (shell scripts that
// render with prism itself), a failing one, and bad arguments.
#include "tools/bench/compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>

#include "assembly/build_scene.h"
#include "image/image_io.h"
#include "scene/pbrt_parser.h"
#include "support/errors.h"
#include "support/process.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

int SppOf(const std::string &text) {
    Diagnostics diag;
    return SceneSamplesPerPixel(ParsePbrtString(text, "s.pbrt", diag));
}

TEST(Compare, DefaultLadderHalvesAndDoublesTheScenesCount) {
    EXPECT_EQ(DefaultLadder(16), (std::vector<int>{2, 4, 8, 16, 32}));
    EXPECT_EQ(DefaultLadder(4), (std::vector<int>{1, 2, 4, 8}));
    EXPECT_EQ(DefaultLadder(1), (std::vector<int>{1, 2}));
}

TEST(Compare, SampleCountRewriteKeepsTheRestOfTheFile) {
    const std::string text =
        "# Sampler \"halton\" in a comment is not a directive\n"
        "Sampler \"halton\" \"integer pixelsamples\" 16 \"string note\" \"Sampler\"\n"
        "Film \"image\"\nWorldBegin\nShape \"sphere\"\n";
    const std::string out = SetPbrtV3SampleCount(text, 8, "s.pbrt");
    EXPECT_EQ(out,
              "# Sampler \"halton\" in a comment is not a directive\n"
              "Sampler \"halton\" \"integer pixelsamples\" [ 8 ] \"string note\" \"Sampler\"\n"
              "Film \"image\"\nWorldBegin\nShape \"sphere\"\n");
    EXPECT_EQ(SppOf(out), 8);
    // A bracketed count, and a second Sampler (the last wins in pbrt): both rewritten.
    const std::string two =
        "Sampler \"random\" \"integer pixelsamples\" [ 4 ]\n"
        "Sampler \"sobol\" \"integer pixelsamples\" [\n 64\n]\nWorldBegin\n";
    EXPECT_EQ(SetPbrtV3SampleCount(two, 2, "s.pbrt"),
              "Sampler \"random\" \"integer pixelsamples\" [ 2 ]\n"
              "Sampler \"sobol\" \"integer pixelsamples\" [ 2 ]\nWorldBegin\n");
}

TEST(Compare, SampleCountRewriteAddsWhatTheFileLeavesToDefaults) {
    // No Sampler: pbrt-v3's default (halton) with the count, before WorldBegin.
    EXPECT_EQ(SetPbrtV3SampleCount("Film \"image\"\nWorldBegin\n", 32, "s.pbrt"),
              "Film \"image\"\nSampler \"halton\" \"integer pixelsamples\" [ 32 ]\nWorldBegin\n");
    // A Sampler without a count gets one.
    const std::string bare = SetPbrtV3SampleCount("Sampler \"halton\"\nWorldBegin\n", 4, "s.pbrt");
    EXPECT_EQ(bare, "Sampler \"halton\" \"integer pixelsamples\" [ 4 ]\nWorldBegin\n");
    EXPECT_EQ(SppOf(bare), 4);
    // Stratified: xsamples x ysamples, split as pbrt-v4's --spp splits it.
    const std::string strat = SetPbrtV3SampleCount(
        "Sampler \"stratified\" \"integer xsamples\" [ 4 ] \"bool jitter\" \"true\"\nWorldBegin\n",
        8, "s.pbrt");
    EXPECT_EQ(strat,
              "Sampler \"stratified\" \"integer ysamples\" [ 4 ] \"integer xsamples\" [ 2 ] "
              "\"bool jitter\" \"true\"\nWorldBegin\n");
    EXPECT_EQ(SppOf(strat), 8);
    EXPECT_NE(ErrorOf<SceneError>([] {
                  SetPbrtV3SampleCount("Shape \"sphere\"\n", 4, "s.pbrt");
              }).find("s.pbrt: error: no WorldBegin"),
              std::string::npos);
}

TEST(Compare, ResolutionRewriteSetsOrAddsTheFilm) {
    EXPECT_EQ(SetPbrtResolution("Film \"image\" \"integer xresolution\" [ 640 ] "
                                "\"string filename\" \"a.exr\"\nWorldBegin\n",
                                32, 24, "image", "s.pbrt"),
              "Film \"image\" \"integer yresolution\" [ 24 ] \"integer xresolution\" [ 32 ] "
              "\"string filename\" \"a.exr\"\nWorldBegin\n");
    EXPECT_EQ(SetPbrtResolution("WorldBegin\n", 8, 6, "rgb", "s.pbrt"),
              "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 6 ]\n"
              "WorldBegin\n");
}

TEST(Compare, FitsAndTheCountAndTimeOfATarget) {
    // error = 0.1 n^-0.5 and 0.2 s of start-up plus 0.01 s a sample, exactly.
    const std::vector<int> n{1, 2, 4, 8};
    std::vector<double> e, t;
    for (int k : n) e.push_back(0.1 / std::sqrt(k)), t.push_back(0.2 + 0.01 * k);
    const CompareFit f = FitRenderer(n, e, t);
    ASSERT_TRUE(f.error.ok);
    EXPECT_NEAR(f.error.b, -0.5, 1e-12);
    EXPECT_NEAR(std::exp(f.error.a), 0.1, 1e-12);
    EXPECT_NEAR(f.t0, 0.2, 1e-12);
    EXPECT_NEAR(f.c, 0.01, 1e-12);
    ASSERT_TRUE(SppToError(f.error, 0.01).has_value());
    EXPECT_NEAR(*SppToError(f.error, 0.01), 100, 1e-9);
    EXPECT_NEAR(f.Seconds(100), 1.2, 1e-12);
    // An error that no longer falls (a bias floor) is never reached; one point fits nothing.
    EXPECT_FALSE(SppToError(FitLogLog({1, 2, 4}, {0.05, 0.05, 0.049}), 0.01).has_value());
    EXPECT_FALSE(FitLogLog({1}, {0.1}).ok);
    EXPECT_FALSE(FitLogLog({1, 2}, {0.1, std::nan("")}).ok) << "a non-finite point is left out";
    // Times that do not grow (start-up only) cost nothing per sample.
    const CompareFit flat = FitRenderer(n, e, {0.3, 0.29, 0.31, 0.28});
    EXPECT_EQ(flat.c, 0);
    EXPECT_NEAR(flat.t0, 0.295, 1e-12);
}

TEST(Compare, EqualErrorLine) {
    EXPECT_EQ(EqualErrorLine(0.0125, {{"prism", 1.5, false},
                                      {"pbrt-v3", 4.5, false},
                                      {"pbrt-v4", std::nullopt, true},
                                      {"pbrt-v4", std::nullopt, false}}),
              "equal-error 0.0125: prism 1.50 s, pbrt-v3 4.50 s (ratio 3.00), pbrt-v4 failed, "
              "pbrt-v4 never");
}

// ---- the command ---------------------------------------------------------------------------

const char *kScene =
    "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\n"
    "Sampler \"halton\" \"integer pixelsamples\" 4\n"
    "Film \"image\" \"integer xresolution\" 24 \"integer yresolution\" 24\n"
    "WorldBegin\nLightSource \"distant\" \"point from\" [1 1 5] \"point to\" [0 0 0]\n"
    "Material \"matte\"\nShape \"sphere\"\n";

// A fake pbrt: logs its arguments (and the Sampler line of its standard input) to LOG, then
// renders the scene it is given with prism, `times` times over (so that it spends that many
// times Prism's CPU on the same image). With `upgrade` it answers --upgrade FILE with the file.
std::string FakeRenderer(const fs::path &dir, const std::string &name, int times,
                         const std::string &failWith = "") {
    std::string s = "#!/bin/sh\nLOG='" + (dir / (name + ".log")).string() + "'\n";
    s += "echo \"$@\" >> \"$LOG\"\n";
    if (!failWith.empty()) {
        const std::string path =
            WriteTestFile(dir / name, s + "echo '" + failWith + "' >&2\nexit 1\n");
        fs::permissions(path, fs::perms::owner_all);
        return path;
    }
    s += "if [ \"$1\" = --upgrade ]; then cat \"$2\"; exit 0; fi\n"
         "spp=''; out=''; file=''\n"
         "while [ $# -gt 0 ]; do case \"$1\" in\n"
         "  --spp) spp=$2; shift 2;; --outfile) out=$2; shift 2;;\n"
         "  --nthreads|--logdir) shift 2;; --quiet) shift;; *) file=$1; shift;; esac; done\n"
         "in=\"$out.in.pbrt\"\n"
         "if [ -z \"$file\" ]; then cat > \"$in\"; else cp \"$file\" \"$in\"; fi\n"
         "grep '^Sampler' \"$in\" >> \"$LOG\"\n"
         "sppArg=''; [ -n \"$spp\" ] && sppArg=\"--spp $spp\"\n"
         "i=0; while [ $i -lt " +
         std::to_string(times) +
         " ]; do\n"
         "  '" PRISM_BINARY
         "' render \"$in\" $sppArg --threads 1 -o \"$out\" -q || exit 1\n"
         "  i=$((i + 1)); done\n";
    const std::string path = WriteTestFile(dir / name, s);
    fs::permissions(path, fs::perms::owner_all);
    return path;
}

// The last line of the output.
std::string LastLine(const std::string &s) {
    std::string t = s;
    while (!t.empty() && t.back() == '\n') t.pop_back();
    return t.substr(t.rfind('\n') + 1);
}

TEST(CompareCli, FakeRenderersAtTwiceTheCostComeOutSlower) {
    const fs::path dir = TempDir("fakes");
    WriteTestFile(dir / "s.pbrt", kScene);
    const std::string v3 = FakeRenderer(dir, "fake-v3", 2), v4 = FakeRenderer(dir, "fake-v4", 2);
    const RunResult r =
        RunPrism("bench compare s.pbrt --against pbrt-v3=" + v3 + " --against pbrt-v4=" + v4 +
                     " --spp 1,2,4 --reference-spp 16 --repeats 1 --res 20x16 --own-reference"
                     " --out out",
                 dir);
    ASSERT_EQ(r.exitCode, 0) << r.Both();
    const std::string last = LastLine(r.out);
    std::smatch m;
    ASSERT_TRUE(std::regex_match(last, m,
                                 std::regex("equal-error ([0-9.e-]+): prism ([0-9.]+) s, pbrt-v3 "
                                            "([0-9.]+) s \\(ratio ([0-9.]+)\\), pbrt-v4 ([0-9.]+) "
                                            "s \\(ratio ([0-9.]+)\\)")))
        << last;
    // The same images for twice the CPU: both are slower than Prism (the ratio is CPU time, so
    // the machine's load does not decide it).
    EXPECT_GT(std::stod(m[4]), 1.2) << r.out;
    EXPECT_GT(std::stod(m[6]), 1.2) << r.out;
    // The target is pbrt-v3's error at the file's 4 spp; the reference is pbrt-v3's.
    EXPECT_NE(r.out.find("target error " + std::string(m[1]) + " (pbrt-v3's error at 4 spp)"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("reference: pbrt-v3 at 16 spp"), std::string::npos) << r.out;
    // --own-reference: each against its own 16-spp image; the fakes render Prism's images, so
    // the references do not differ.
    EXPECT_NE(r.out.find("prism's own reference at 16 spp: rel. RMSE 0 against the shared one"),
              std::string::npos)
        << r.out;
    // pbrt-v3 got the file on stdin with the count rewritten, in the scene's folder; pbrt-v4 the
    // upgraded file with --spp.
    const std::string log3 = ReadFile(dir / "fake-v3.log"), log4 = ReadFile(dir / "fake-v4.log");
    for (int n : {1, 2, 4, 16})
        EXPECT_NE(
            log3.find("Sampler \"halton\" \"integer pixelsamples\" [ " + std::to_string(n) + " ]"),
            std::string::npos)
            << log3;
    EXPECT_NE(log3.find("--nthreads 1 --quiet --logdir"), std::string::npos) << log3;
    EXPECT_NE(log4.find("--upgrade " + (dir / "s.pbrt").string()), std::string::npos) << log4;
    EXPECT_NE(log4.find("--nthreads 1 --quiet --spp 2 --outfile"), std::string::npos) << log4;
    // --res reached every renderer: the images are 20x16.
    for (const char *image : {"prism-4.exr", "pbrt-v3-4.exr", "pbrt-v4-1.exr"})
        EXPECT_EQ(ReadImage((dir / "out/images" / image).string()).width, 20) << image;
    // One CSV row per renderer and count, the fits, the plot.
    const std::string csv = ReadFile(dir / "out/compare.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 3 * 3) << csv;
    EXPECT_NE(csv.find("\npbrt-v4,4,0,"), std::string::npos) << csv;
    EXPECT_TRUE(fs::exists(dir / "out/fit.csv"));
    EXPECT_TRUE(fs::exists(dir / "out/compare.png")) << r.err;
    EXPECT_TRUE(fs::exists(dir / "out/images/prism-4.exr"));
}

TEST(CompareCli, AFailingRendererIsReportedAndNothingIsLeftBehind) {
    const fs::path dir = TempDir("failing"), tmp = TempDir("tmp");
    WriteTestFile(dir / "s.pbrt", kScene);
    const std::string bad = FakeRenderer(dir, "broken", 1, "boom: cannot render");
    const RunResult r = RunPrism("bench compare s.pbrt --against pbrt-v3=" + bad +
                                     " --spp 1,2 --reference-spp 8 --repeats 2",
                                 dir, "TMPDIR=" + ShellQuoted(tmp.string()));
    EXPECT_EQ(r.exitCode, 3) << r.Both();
    EXPECT_NE(r.out.find("pbrt-v3: exit status 1: boom: cannot render"), std::string::npos)
        << r.out;
    // Prism renders the reference instead, and its own target.
    EXPECT_NE(r.out.find("reference: prism at 8 spp"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("(prism's error at 2 spp)"), std::string::npos) << r.out;
    EXPECT_TRUE(std::regex_match(LastLine(r.out),
                                 std::regex("equal-error [0-9.e-]+: prism [0-9.]+ s, pbrt-v3 "
                                            "failed")))
        << r.out;
    // Without --out the images went to a temporary folder, removed at the end.
    EXPECT_TRUE(fs::is_empty(tmp));
    // A scene pbrt cannot read is reported, not guessed at.
    WriteTestFile(dir / "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const RunResult obj =
        RunPrism("bench compare t.obj --against pbrt-v3=" + bad + " --spp 1 --repeats 1", dir);
    EXPECT_EQ(obj.exitCode, 3) << obj.Both();
    EXPECT_NE(obj.out.find("pbrt-v3: cannot render obj scenes (pbrt files only)"),
              std::string::npos)
        << obj.out;
}

TEST(CompareCli, BadArgumentsAreUsageErrors) {
    const fs::path dir = TempDir("usage");
    WriteTestFile(dir / "s.pbrt", kScene);
    RunResult r = RunPrism("bench compare s.pbrt --against mitsuba=/bin/true", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("--against takes pbrt-v3=PATH or pbrt-v4=PATH, not \"mitsuba=/bin/true\""),
              std::string::npos)
        << r.err;
    r = RunPrism("bench compare s.pbrt --against pbrt-v3=no-such-pbrt", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("\"no-such-pbrt\" is not an executable file"), std::string::npos) << r.err;
    r = RunPrism("bench compare s.pbrt --spp 4,0", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("--spp takes counts from 1 to 65536"), std::string::npos) << r.err;
    r = RunPrism("bench compare missing.pbrt", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("cannot open file"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace prism
