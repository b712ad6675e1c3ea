// End-to-end tests of the prism executable: rendering, determinism, ray queries and the
// handling of malformed input (exit status, located message, no output file).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "image/image.h"
#include "image/image_compare.h"
#include "image/image_io.h"
#include "support/process.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

TEST(Cli, RendersWhittedAtSmallSize) {
    fs::path dir = TempDir("whitted");
    RunResult r =
        RunPrism("render '" + Source + "/scenes/whitted.pbrt' --res 64x48 -o out.exr --quiet", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Image img = ReadImage((dir / "out.exr").string());
    EXPECT_EQ(img.width, 64);
    EXPECT_EQ(img.height, 48);
    Image golden = ReadImage(Source + "/tests/golden/whitted_64x48.exr");
    ImageDiff d = CompareImages(img, golden, 0.05f);
    // A regression image, not a reference: Prism rendered it itself (checked by eye), so it
    // catches unintended changes, not errors it already had (correctness against pbrt-v3 is
    // docs/PBRT3_COMPARISON.md). Small tolerances absorb compiler and ISA differences.
    EXPECT_LT(d.rmse, 0.01) << "mean abs " << d.meanAbs << " max " << d.maxAbs;
    EXPECT_LT(d.badPixels, 10);
}

TEST(Cli, ImageIsIndependentOfThreadCount) {
    fs::path dir = TempDir("threads");
    std::string scene = "'" + Source + "/scenes/whitted.pbrt' --res 64x48 --spp 4 --quiet";
    ASSERT_EQ(RunPrism("render " + scene + " --threads 1 -o one.exr", dir).exitCode, 0);
    ASSERT_EQ(RunPrism("render " + scene + " --threads 2 -o two.exr", dir).exitCode, 0);
    Image a = ReadImage((dir / "one.exr").string()), b = ReadImage((dir / "two.exr").string());
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_TRUE(a.pixels == b.pixels) << "images differ between 1 and 2 threads";
}

TEST(Cli, RenderReportsStatistics) {
    fs::path dir = TempDir("stats");
    RunResult r = RunPrism("render '" + Source + "/scenes/whitted.pbrt' --res 32x24 -o s.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("BVH build"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("refraction"), std::string::npos);
    EXPECT_NE(r.err.find("Mrays/s"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir / "s.png"));
}

TEST(Cli, IntegratorAndGlossySamplesOptions) {
    fs::path dir = TempDir("integrator");
    std::string scene = "render '" + Source + "/scenes/glossy.pbrt' --res 24x16 --spp 1 ";
    RunResult d = RunPrism(scene + "--glossy-samples 2 -o d.png", dir);
    ASSERT_EQ(d.exitCode, 0) << d.err;
    EXPECT_NE(d.err.find("distribution integrator"), std::string::npos) << d.err;
    EXPECT_EQ(d.err.find("glossy 0;"), std::string::npos) << d.err;
    RunResult w = RunPrism(scene + "--integrator whitted -o w.png", dir);
    ASSERT_EQ(w.exitCode, 0) << w.err;
    EXPECT_NE(w.err.find("whitted integrator"), std::string::npos) << w.err;
    EXPECT_NE(w.err.find("glossy 0;"), std::string::npos) << w.err;
    // Whitted names the rough glass it renders smooth; the distribution integrator does not.
    EXPECT_NE(w.err.find("rough glass"), std::string::npos) << w.err;
    EXPECT_EQ(d.err.find("rough glass"), std::string::npos) << d.err;
    RunResult p = RunPrism(scene + "--integrator path -o p.png", dir);
    ASSERT_EQ(p.exitCode, 0) << p.err;
    EXPECT_NE(p.err.find("path integrator"), std::string::npos) << p.err;
    EXPECT_NE(RunPrism(scene + "--integrator nosuchintegrator -o p.png", dir).exitCode, 0);
    // --sampler draws another sampler's samples; the path integrator draws pbrt-v4's zsobol.
    RunResult z = RunPrism(scene + "--integrator path --sampler zsobol -o z.png", dir);
    ASSERT_EQ(z.exitCode, 0) << z.err;
    EXPECT_NE(ReadFile(dir / "z.png"), ReadFile(dir / "p.png"));
    RunResult h = RunPrism(scene + "--integrator path --sampler maxmindist -o h.png", dir);
    ASSERT_EQ(h.exitCode, 0) << h.err;
    EXPECT_NE(h.err.find("sampler \"maxmindist\" is replaced by Prism's stratified sampler"),
              std::string::npos)
        << h.err;
    EXPECT_EQ(RunPrism(scene + "--sampler nosuchsampler -o s.png", dir).exitCode, 2);
    EXPECT_FALSE(fs::exists(dir / "s.png"));
    EXPECT_NE(RunPrism(scene + "--glossy-samples 0 -o p.png", dir).exitCode, 0);
}

TEST(Cli, BadInputFailsCleanly) {
    fs::path bad = fs::path(Source) / "tests/bad";
    std::ifstream cases(bad / "cases.txt");
    ASSERT_TRUE(cases) << "missing tests/bad/cases.txt";
    std::string line;
    int n = 0;
    std::set<std::string> files;
    while (std::getline(cases, line)) {
        if (line.empty() || line[0] == '#') continue;
        auto bar1 = line.find(" | "), bar2 = line.find(" | ", bar1 + 3);
        ASSERT_NE(bar2, std::string::npos) << line;
        auto bar3 = line.find(" | ", bar2 + 3);
        std::string file = line.substr(0, bar1);
        int status = std::stoi(line.substr(bar1 + 3, bar2 - bar1 - 3));
        std::string fragment =
            line.substr(bar2 + 3, bar3 == std::string::npos ? std::string::npos : bar3 - bar2 - 3);
        // A 4th column replaces the default "--res 16x16" with other arguments.
        std::string extra = bar3 == std::string::npos ? "--res 16x16" : line.substr(bar3 + 3);
        files.insert(file);
        fs::path dir = TempDir("bad");
        std::string scenePath = (bad / file).string();
        RunResult r = RunPrism("render '" + scenePath + "' -o out.png " + extra, dir);
        EXPECT_EQ(r.exitCode, status) << file << ": " << r.err;
        if (fragment[0] == '@') fragment = scenePath + ":" + fragment.substr(1);
        EXPECT_NE(r.err.find(fragment), std::string::npos)
            << file << ": expected \"" << fragment << "\" in: " << r.err;
        // Exactly one error line (a message may quote a library's "read error: ...").
        size_t errors = 0;
        std::istringstream errLines(r.err);
        for (std::string l; std::getline(errLines, l);)
            errors += l.find("error:") != std::string::npos;
        EXPECT_EQ(errors, 1u) << file << ": " << r.err;
        // The error is one line: it ends the output and names what is wrong.
        size_t at = r.err.find("error:");
        if (at != std::string::npos)
            EXPECT_EQ(r.err.find('\n', at), r.err.size() - 1) << file << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir / "out.png")) << file << " left an output file";
        for (const auto &e : fs::directory_iterator(dir))
            ADD_FAILURE() << file << " left " << e.path();
        ++n;
    }
    EXPECT_GE(files.size(), 40u) << "tests/bad/ should hold at least 40 malformed inputs";
}

TEST(Cli, BadOptionsExitWithStatus2) {
    fs::path dir = TempDir("opts");
    std::string scene = "'" + Source + "/scenes/whitted.pbrt'";
    EXPECT_EQ(RunPrism("render " + scene + " --res 0x10 -o a.png", dir).exitCode, 2);
    EXPECT_EQ(RunPrism("render " + scene + " --spp 0 -o a.png", dir).exitCode, 2);
    EXPECT_EQ(RunPrism("render " + scene + " -o a.xyz", dir).exitCode, 2);
    EXPECT_EQ(RunPrism("render " + scene + " -o no/such/dir/a.png", dir).exitCode, 2);
    EXPECT_EQ(RunPrism("frobnicate", dir).exitCode, 2);
    RunResult mem = RunPrism("render " + scene + " --max-memory 12Q -o a.png", dir);
    EXPECT_EQ(mem.exitCode, 2);
    EXPECT_NE(mem.err.find("error: --max-memory expects a size such as 512M or 8G"),
              std::string::npos)
        << mem.err;
    EXPECT_FALSE(fs::exists(dir / "a.png"));
}

// The accuracy knobs of `prism render` (docs/SHAPES.md): --cutoff 0 writes the image of a
// render without it, byte for byte; a cutoff reports the rays it saved; the other knobs are
// echoed; bad values exit with status 2 and write nothing.
TEST(Cli, AccuracyKnobOptions) {
    fs::path dir = TempDir("knobs");
    std::string scene = "'" + Source + "/scenes/whitted.pbrt' --res 32x24";
    ASSERT_EQ(RunPrism("render " + scene + " -q -o plain.exr", dir).exitCode, 0);
    ASSERT_EQ(RunPrism("render " + scene + " -q --cutoff 0 -o zero.exr", dir).exitCode, 0);
    EXPECT_EQ(ReadFile(dir / "plain.exr"), ReadFile(dir / "zero.exr"));
    RunResult cut = RunPrism("render " + scene + " --no-progress --cutoff 0.01 -o c.png", dir);
    ASSERT_EQ(cut.exitCode, 0) << cut.err;
    EXPECT_NE(cut.err.find("rays saved by cutoff"), std::string::npos) << cut.err;
    RunResult knobs = RunPrism("render " + scene +
                                   " --no-progress --offset-epsilon 0.001 --robust "
                                   "--bvh-quality low -o k.png",
                               dir);
    ASSERT_EQ(knobs.exitCode, 0) << knobs.err;
    EXPECT_NE(knobs.err.find("offset epsilon 0.001, BVH low quality, robust"), std::string::npos)
        << knobs.err;
    RunResult none = RunPrism("render " + scene + " --no-progress --offset none -o n.png", dir);
    EXPECT_NE(none.err.find("offset none"), std::string::npos) << none.err;
    RunResult plain = RunPrism("render " + scene + " --no-progress -o p.png", dir);
    EXPECT_EQ(plain.err.find("accuracy:"), std::string::npos) << plain.err;
    for (const char *bad : {"--cutoff -1", "--cutoff x", "--offset fixed", "--offset-epsilon 0",
                            "--offset none --offset-epsilon 1e-3", "--bvh-quality ultra"}) {
        RunResult r = RunPrism("render " + scene + " " + bad + " -o bad.png", dir);
        EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir / "bad.png")) << bad;
    }
}

// The libraries report a memory limit without naming a flag; the app adds it, exactly once.
TEST(Cli, MemoryBudgetErrorNamesTheFlagOnce) {
    fs::path dir = TempDir("budget");
    const std::string flag = "(--max-memory)";
    for (const char *args : {"budget_includes.pbrt' --max-memory 8K --res 16x16",
                             "ply_budget.pbrt' --max-memory 100K --res 16x16",
                             "budget_film_texture.pbrt' --max-memory 60K --res 16x16",
                             "tex_big_png.pbrt' --max-memory 40K --res 16x16",
                             "budget_film_ply.pbrt' --max-memory 160K --res 32x32",
                             "budget_resolution.pbrt' --max-memory 1G"}) {
        RunResult r = RunPrism("render '" + Source + "/tests/bad/" + args + " -o a.png", dir);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        size_t at = r.err.find(flag);
        ASSERT_NE(at, std::string::npos) << r.err;
        EXPECT_EQ(r.err.find(flag, at + 1), std::string::npos) << r.err;
        EXPECT_EQ(at + flag.size() + 1, r.err.size())
            << "the message ends with the flag: " << r.err;
        EXPECT_FALSE(fs::exists(dir / "a.png"));
    }
}

std::string SphereScene(int w, int h, int spp);

TEST(Cli, InfoDescribesScene) {
    fs::path dir = TempDir("info");
    RunResult r = RunPrism("info '" + Source + "/scenes/quadrics.pbrt'", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("shapes:     13 ("), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("torus 2"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("triangles:  2"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("lights:     2 (point 1, spot 1)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("bounds:"), std::string::npos);
    EXPECT_NE(r.out.find("warnings:   0"), std::string::npos);
    EXPECT_EQ(RunPrism("info missing.pbrt", dir).exitCode, 2);

    // Warnings that only building the scene gives (sampler, material) are listed too.
    std::string warn = SphereScene(8, 8, 4);
    warn.replace(warn.find("\"halton\""), 8, "\"maxmindist\"");
    std::ofstream(dir / "warn.pbrt") << warn;
    r = RunPrism("info warn.pbrt", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("warn.pbrt:4:1: warning: sampler \"maxmindist\" is replaced"),
              std::string::npos)
        << r.out;
    // Which integrator runs, and why: the default, the scene's line, or --integrator.
    EXPECT_NE(r.out.find("integrator: path (pbrt-v3's default: the scene names no Integrator)"),
              std::string::npos)
        << r.out;
    std::ofstream(dir / "path.pbrt") << "Integrator \"path\"\n" << SphereScene(8, 8, 4);
    r = RunPrism("info path.pbrt", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("integrator: path (Integrator \"path\" at path.pbrt:1:1)"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("indirect illumination: on (Integrator \"path\" at path.pbrt:1:1)"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("kernel:     none (path integrator)"), std::string::npos) << r.out;
}

// Red channel minus blue, summed over the left and the right half of an image.
std::pair<double, double> RedMinusBlueByHalf(const Image &img) {
    double left = 0, right = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            (2 * x < img.width ? left : right) += img.At(x, y, 0) - img.At(x, y, 2);
    return {left, right};
}

// --lookat frames a right-handed OBJ (or glTF) world as its default camera does: looking
// down -z with +y up, world +x is on the image's right. It used to be pbrt's left-handed
// frame everywhere, which mirrored OBJ and glTF renders. In a pbrt world it is the file's
// LookAt, bit for bit.
TEST(Cli, LookAtShowsWorldPlusXOnTheRightOfARightHandedWorld) {
    fs::path dir = TempDir("lookat");
    std::ofstream(dir / "m.mtl") << "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n";
    std::ofstream(dir / "s.obj") << "mtllib m.mtl\n"
                                    "v 0.2 -1 0\nv 2 -1 0\nv 2 1 0\nv 0.2 1 0\n"
                                    "v -2 -1 0\nv -0.2 -1 0\nv -0.2 1 0\nv -2 1 0\n"
                                    "usemtl red\nf 1 2 3 4\nusemtl blue\nf 5 6 7 8\n";
    RunResult r =
        RunPrism("render s.obj -o obj.exr -q --res 32x16 --lookat 0,0,5,0,0,0,0,1,0 --fov 60", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto [left, right] = RedMinusBlueByHalf(ReadImage((dir / "obj.exr").string()));
    EXPECT_LT(left, 0) << "blue (world -x) belongs on the left";
    EXPECT_GT(right, 0) << "red (world +x) belongs on the right";

    const std::string world =
        "WorldBegin\nLightSource \"distant\" \"point from\" [0 0 5]\n"
        "Material \"matte\" \"rgb Kd\" [1 0 0]\n"
        "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] "
        "\"point3 P\" [0.2 -1 0  2 -1 0  2 1 0  0.2 1 0]\n"
        "Material \"matte\" \"rgb Kd\" [0 0 1]\n"
        "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] "
        "\"point3 P\" [-2 -1 0  -0.2 -1 0  -0.2 1 0  -2 1 0]\n";
    const std::string film =
        "Film \"image\" \"integer xresolution\" 32 \"integer yresolution\" 16\n";
    std::ofstream(dir / "own.pbrt") << "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" "
                                       "\"float fov\" 60\n"
                                    << film << world;
    std::ofstream(dir / "flag.pbrt") << "Camera \"perspective\" \"float fov\" 60\n"
                                     << film << world;
    ASSERT_EQ(RunPrism("render own.pbrt -o own.exr -q", dir).exitCode, 0);
    ASSERT_EQ(RunPrism("render flag.pbrt -o flag.exr -q --lookat 0,0,5,0,0,0,0,1,0", dir).exitCode,
              0);
    Image own = ReadImage((dir / "own.exr").string()),
          flag = ReadImage((dir / "flag.exr").string());
    EXPECT_EQ(own.pixels, flag.pixels);
    // pbrt's left-handed frame: looking down -z, world +x is on the left.
    EXPECT_GT(RedMinusBlueByHalf(own).first, 0);
}

TEST(Cli, TraceReportsHitsMissesAndLimits) {
    fs::path dir = TempDir("trace");
    std::ofstream(dir / "s.pbrt")
        << "Camera \"perspective\"\nWorldBegin\n"
           "AttributeBegin\nTranslate 0 0 5\nShape \"sphere\" \"float radius\" 1\nAttributeEnd\n"
           "AttributeBegin\nReverseOrientation\nTranslate 10 0 5\nShape \"sphere\"\nAttributeEnd\n"
           "Shape \"trianglemesh\" \"integer indices\" [0 1 2] \"point3 P\" [-1 -1 20  1 -1 20  0 "
           "1 20]\n"
           "WorldEnd\n";
    std::ofstream(dir / "rays.txt") << "# origin direction [tmin tmax]\n"
                                       "0 0 0  0 0 1\n"
                                       "0 0 0  0 0 2   # unnormalized: t halves\n"
                                       "0 5 0  0 0 1\n"
                                       "0 0 0  0 0 1  0 3.5\n"
                                       "0 0 0  0 0 1  4.5 100\n"
                                       "10 0 0  0 0 1\n"
                                       "0 0 10  0 0 1\n";
    RunResult r = RunPrism("trace s.pbrt --rays rays.txt --quiet", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(r.out);
    std::vector<std::string> got;
    for (std::string l; std::getline(lines, l);) got.push_back(l);
    ASSERT_EQ(got.size(), 7u) << r.out;
    EXPECT_EQ(got[0], "hit 4 0 0 4 0 0 -1 0 0");
    EXPECT_EQ(got[1], "hit 2 0 0 4 0 0 -1 0 0");
    EXPECT_EQ(got[2], "miss");
    EXPECT_EQ(got[3], "miss");                    // tmax stops before the sphere
    EXPECT_EQ(got[4], "hit 6 0 0 6 0 0 1 0 0");   // tmin skips the near side
    EXPECT_EQ(got[5], "hit 4 10 0 4 0 0 1 1 0");  // ReverseOrientation flips n
    // The triangle, through Embree's own intersector: t and p to float rounding (AVX2 and
    // AVX-512 kernels round differently), n = (p1-p0) x (p2-p0) exactly.
    std::istringstream tri(got[6]);
    std::string word;
    float t, px, py, pz;
    std::string rest;
    tri >> word >> t >> px >> py >> pz;
    std::getline(tri, rest);
    EXPECT_EQ(word, "hit") << got[6];
    EXPECT_NEAR(t, 10.f, 1e-5f) << got[6];
    EXPECT_NEAR(px, 0.f, 1e-6f) << got[6];
    EXPECT_NEAR(py, 0.f, 1e-6f) << got[6];
    EXPECT_EQ(pz, 20.f) << got[6];
    EXPECT_EQ(rest, " 0 0 1 2 0") << got[6];
    RunResult occ = RunPrism("trace s.pbrt --rays rays.txt --occluded --quiet", dir);
    ASSERT_EQ(occ.exitCode, 0);
    EXPECT_EQ(occ.out, "1\n1\n0\n0\n1\n1\n1\n");
    std::ofstream(dir / "bad.txt") << "0 0 0 0 0 1\n0 0 0 0 1\n";
    RunResult bad = RunPrism("trace s.pbrt --rays bad.txt -o out.txt", dir);
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("bad.txt:2:"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(dir / "out.txt"));
}

// ---- prism batch ----------------------------------------------------------------------------

// A sphere under a point light at the given film size and sample count.
std::string SphereScene(int w, int h, int spp) {
    return "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
           "Film \"image\" \"integer xresolution\" " +
           std::to_string(w) + " \"integer yresolution\" " + std::to_string(h) +
           "\n"
           "Sampler \"halton\" \"integer pixelsamples\" " +
           std::to_string(spp) +
           "\n"
           "WorldBegin\nLightSource \"point\" \"point from\" [0 3 -3] \"rgb I\" [20 20 20]\n"
           "Material \"glass\"\nShape \"sphere\"\nWorldEnd\n";
}

// The line of report.json that describes `scene` (the writer puts one scene per line).
std::string ReportLine(const fs::path &outDir, const std::string &scene) {
    std::istringstream in(ReadFile(outDir / "report.json"));
    for (std::string l; std::getline(in, l);)
        if (l.find("\"scene\": \"" + scene + "\"") != std::string::npos ||
            l.find("/" + scene + "\", \"output\"") != std::string::npos)
            return l;
    return "";
}

bool HasStatus(const fs::path &outDir, const std::string &scene, const std::string &status) {
    return ReportLine(outDir, scene).find("\"status\": \"" + status + "\"") != std::string::npos;
}

TEST(Batch, ReportsFailuresKeepsImagesAndSkipsUpToDate) {
    fs::path dir = TempDir("batch");
    fs::create_directories(dir / "in/sub");
    std::ofstream(dir / "in/a.pbrt") << SphereScene(16, 12, 1);
    std::ofstream(dir / "in/sub/b.pbrt") << SphereScene(12, 8, 1);
    std::ofstream(dir / "in/broken.pbrt") << "Camera \"perspective\"\nWorldBegin\nSphere 1\n";
    std::ofstream(dir / "in/bad.obj") << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
    std::ofstream(dir / "in/notes.txt") << "not a scene\n";
    // A file that another scene includes is a fragment, not a scene of its own.
    std::string withInclude = SphereScene(8, 8, 1);
    withInclude.insert(withInclude.find("WorldEnd"), "Include \"sub/part.pbrt\"\n");
    std::ofstream(dir / "in/c.pbrt") << withInclude;
    std::ofstream(dir / "in/sub/part.pbrt") << "Shape \"sphere\" \"float radius\" 0.5\n";
    // A PLY file is a scene of its own, unless a scene names it (plymesh): then it is a mesh.
    const char *ply =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    fs::create_directories(dir / "in/mesh");
    std::ofstream(dir / "in/lone.ply") << ply;
    std::ofstream(dir / "in/mesh/tri.ply") << ply;
    std::string withMesh = SphereScene(8, 8, 1);
    withMesh.insert(withMesh.find("WorldEnd"),
                    "Shape \"plymesh\" \"string filename\" [ \"mesh/tri.ply\" ]\n");
    std::ofstream(dir / "in/d.pbrt") << withMesh;

    RunResult r = RunPrism("batch in -o out --quiet", dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    fs::path out = dir / "out";
    ASSERT_TRUE(fs::exists(out / "report.json")) << r.err;
    ASSERT_TRUE(fs::exists(out / "summary.txt"));
    EXPECT_TRUE(HasStatus(out, "a.pbrt", "ok")) << ReadFile(out / "report.json");
    EXPECT_TRUE(HasStatus(out, "b.pbrt", "ok"));
    EXPECT_TRUE(HasStatus(out, "broken.pbrt", "failed"));
    EXPECT_TRUE(HasStatus(out, "bad.obj", "failed"));
    EXPECT_NE(ReportLine(out, "broken.pbrt").find("unknown directive"), std::string::npos)
        << ReportLine(out, "broken.pbrt");
    EXPECT_EQ(ReportLine(out, "notes.txt"), "");
    EXPECT_TRUE(HasStatus(out, "c.pbrt", "ok"));
    EXPECT_EQ(ReportLine(out, "part.pbrt"), "");
    EXPECT_TRUE(HasStatus(out, "d.pbrt", "ok"));
    EXPECT_TRUE(HasStatus(out, "lone.ply", "ok"));
    EXPECT_EQ(ReportLine(out, "tri.ply"), "");
    EXPECT_NE(ReadFile(out / "report.json").find("\"ok\": 5, \"skipped\": 0, \"failed\": 2"),
              std::string::npos)
        << ReadFile(out / "report.json");
    EXPECT_NE(ReadFile(out / "summary.txt").find("broken.pbrt"), std::string::npos);
    // Each render's own phases, and the batch's wall time against their sum.
    EXPECT_NE(ReportLine(out, "a.pbrt").find("\"phases\": {\"parse\": "), std::string::npos)
        << ReportLine(out, "a.pbrt");
    EXPECT_EQ(ReportLine(out, "broken.pbrt").find("\"phases\""), std::string::npos);
    EXPECT_NE(ReadFile(out / "report.json").find("\"wall_seconds\": "), std::string::npos);
    EXPECT_NE(ReadFile(out / "summary.txt").find("render phases add up to"), std::string::npos);
    Image a = ReadImage((out / "in_a.png").string());
    EXPECT_EQ(a.width, 16);
    EXPECT_EQ(a.height, 12);
    EXPECT_TRUE(fs::exists(out / "sub_b.png"));
    EXPECT_FALSE(fs::exists(out / "in_broken.png"));
    for (const auto &e : fs::directory_iterator(out))  // no temporaries or logs left behind
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();

    // Re-running skips the images that are newer than their scenes.
    auto stamp = fs::last_write_time(out / "in_a.png");
    r = RunPrism("batch in -o out --quiet", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(HasStatus(out, "a.pbrt", "skipped")) << ReadFile(out / "report.json");
    EXPECT_TRUE(HasStatus(out, "b.pbrt", "skipped"));
    EXPECT_TRUE(HasStatus(out, "broken.pbrt", "failed"));
    EXPECT_EQ(fs::last_write_time(out / "in_a.png"), stamp);

    // An edited scene is re-rendered; --force re-renders everything.
    fs::last_write_time(dir / "in/a.pbrt", stamp + std::chrono::seconds(5));
    r = RunPrism("batch in -o out --quiet", dir);
    EXPECT_TRUE(HasStatus(out, "a.pbrt", "ok")) << ReadFile(out / "report.json");
    EXPECT_TRUE(HasStatus(out, "b.pbrt", "skipped"));
    r = RunPrism("batch in -o out --quiet --force", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(HasStatus(out, "a.pbrt", "ok"));
    EXPECT_TRUE(HasStatus(out, "b.pbrt", "ok"));

    // A list of good scenes exits 0.
    std::ofstream(dir / "list.txt") << "# good ones\nin/a.pbrt\n\nin/sub/b.pbrt\n";
    r = RunPrism("batch list.txt -o out2 --quiet", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "out2/in_a.png"));
}

TEST(Batch, InterruptKeepsFinishedImagesAndReport) {
    fs::path dir = TempDir("batch_int");
    std::ofstream(dir / "fast.pbrt") << SphereScene(16, 12, 1);
    std::ofstream(dir / "slow.pbrt") << SphereScene(1024, 1024, 1024);  // minutes
    std::ofstream(dir / "later.pbrt") << SphereScene(16, 12, 1);
    std::ofstream(dir / "list.txt") << "fast.pbrt\nslow.pbrt\nlater.pbrt\n";
    fs::path out = dir / "out";
    pid_t pid = SpawnPrism(dir, {"batch", "list.txt", "-o", "out", "--threads", "1"}, "batch.log");
    ASSERT_GT(pid, 0);
    // The slow render has started once the fast one is reported finished (its log removed
    // before that) and a render log exists again.
    auto slowStarted = [&] {
        std::error_code ec;
        if (!HasStatus(out, "fast.pbrt", "ok")) return false;
        for (const auto &e : fs::directory_iterator(out, ec)) {
            const std::string name = e.path().filename().string();
            if (name.size() > 8 && name.substr(name.size() - 8) == ".log.tmp") return true;
        }
        return false;
    };
    auto start = std::chrono::steady_clock::now();
    while (!slowStarted() && std::chrono::steady_clock::now() - start < std::chrono::seconds(120))
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_TRUE(fs::exists(out / "fast.png"));
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    kill(pid, SIGINT);
    const int status = WaitOrKill(pid, 60);
    ASSERT_NE(status, -1) << "batch did not stop after SIGINT";
    ASSERT_TRUE(WIFEXITED(status)) << ReadFile(dir / "batch.log");
    EXPECT_EQ(WEXITSTATUS(status), 130) << ReadFile(dir / "batch.log");
    EXPECT_TRUE(HasStatus(out, "fast.pbrt", "ok")) << ReadFile(out / "report.json");
    EXPECT_TRUE(HasStatus(out, "slow.pbrt", "interrupted")) << ReadFile(out / "report.json");
    EXPECT_TRUE(HasStatus(out, "later.pbrt", "pending")) << ReadFile(out / "report.json");
    Image fast = ReadImage((out / "fast.png").string());
    EXPECT_EQ(fast.width, 16);
    EXPECT_FALSE(fs::exists(out / "slow.png"));
    for (const auto &e : fs::directory_iterator(out))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace prism
