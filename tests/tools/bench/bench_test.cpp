// prism bench: the knot generator (against gen_knot.py when it is available), the ceiling
// command on a tiny scene, and the suite's parsing and process pieces.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "assembly/build_scene.h"
#include "scene/load_scene.h"
#include "scene/ply_reader.h"
#include "support/shared.h"
#include "support/temp_dir.h"
#include "tools/bench/ceiling.h"
#include "tools/bench/knot.h"
#include "tools/bench/process.h"
#include "tools/bench/suite.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

TEST(Knot, TriangleCountBoundsAndNormals) {
    KnotMesh m = BuildKnot(40, 8);
    EXPECT_EQ(m.p.size(), 320u);
    EXPECT_EQ(m.n.size(), 320u);
    EXPECT_EQ(m.faces.size(), 640u);
    // Knot curve radius KR + Kr = 2.2, tube radius at most 0.32 * 1.12, centre (0, 2.75, 0).
    double reach = 2.2 + 0.32 * 1.12 + 1e-9, depth = 0.6 + 0.32 * 1.12 + 1e-9;
    double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
    for (const auto &p : m.p) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    }
    EXPECT_GE(lo[0], -reach);
    EXPECT_LE(hi[0], reach);
    EXPECT_GE(lo[1], 2.75 - reach);
    EXPECT_LE(hi[1], 2.75 + reach);
    EXPECT_GE(lo[2], -depth);
    EXPECT_LE(hi[2], depth);
    EXPECT_GT(hi[0] - lo[0], 3.0);  // a knot, not a degenerate blob
    for (const auto &n : m.n) EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-9);
    for (const auto &f : m.faces)
        for (int i : f) EXPECT_TRUE(i >= 0 && i < 320);
}

TEST(Knot, PlyReadableAndSceneBuilds) {
    fs::path dir = TempDir("knot");
    KnotFiles kf = WriteKnotScene(dir.string(), 30, 6, true);
    EXPECT_EQ(kf.triangles, 30u * 6 * 2 + 2);
    EXPECT_TRUE(fs::exists(kf.pov));
    EXPECT_TRUE(fs::exists(kf.povInclude));
    Diagnostics diag;
    PlyMesh ply = ReadPlyFile(kf.ply, diag);
    EXPECT_EQ(ply.P.size(), 180u);
    EXPECT_EQ(ply.N.size(), 180u);
    EXPECT_EQ(ply.indices.size(), 3u * 360);
    KnotMesh m = BuildKnot(30, 6);
    for (size_t i = 0; i < ply.P.size(); ++i) EXPECT_EQ(ply.P[i].y, float(m.p[i][1]));
    SceneDescription desc = LoadScene(kf.pbrt, diag);
    BuildSettings ro;
    RenderScene scene = BuildRenderScene(desc, ro, diag);
    EXPECT_EQ(scene.features.triangles, kf.triangles);
    EXPECT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.resolution, Vec2i(800, 600));
}

// bench's files were written with std::ofstream, which follows a symbolic link at the target
// and truncates whatever it points to; they go through AtomicOutputFile now (a new temporary
// beside the target, renamed over it): a link there is replaced, its target left alone.
TEST(Knot, OutputsReplaceLinksInsteadOfWritingThroughThem) {
    fs::path dir = TempDir("knot_links");
    fs::create_directories(dir / "out");
    std::ofstream(dir / "victim.txt") << "keep";
    for (const char *name : {"knot.ply", "knot.pbrt", "knot.pov", "knot_mesh.inc", "empty.pbrt"})
        fs::create_symlink("../victim.txt", dir / "out" / name);
    WriteKnotScene((dir / "out").string(), 8, 4, true);
    WriteEmptyScene((dir / "out").string());
    EXPECT_EQ(ReadFile(dir / "victim.txt"), "keep");
    for (const char *name : {"knot.ply", "knot.pbrt", "knot.pov", "knot_mesh.inc", "empty.pbrt"}) {
        EXPECT_FALSE(fs::is_symlink(dir / "out" / name)) << name;
        EXPECT_GT(fs::file_size(dir / "out" / name), 0u) << name;
    }
    for (const auto &e : fs::directory_iterator(dir / "out"))
        EXPECT_NE(e.path().extension(), ".tmp") << e.path();  // no temporary left
}

TEST(Knot, EmptySceneRenders) {
    fs::path dir = TempDir("empty");
    std::string empty = WriteEmptyScene(dir.string());
    ChildRun r = RunChild(
        {PRISM_BINARY, "render", empty, "--res", "8x6", "-o", (dir / "x.png").string(), "--quiet"});
    EXPECT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "x.png"));
    EXPECT_GT(r.maxRssKiB, 0);
}

// The generator is a port of ../shared/peers/gen_knot.py: run the script in a scratch copy and
// compare the pbrt text and the PLY bytes.
TEST(Knot, MatchesGenKnotPy) {
    fs::path script = fs::path(PRISM_SHARED_DIR) / "peers" / "gen_knot.py";
    PRISM_REQUIRE_SHARED(script);
    if (!OnPath("python3")) {
        // CI installs python3 (.ci/run): there the comparison must run.
        if (test::InCI()) FAIL() << "python3 missing and CI=true";
        GTEST_SKIP() << "python3 missing";
    }
    fs::path py = TempDir("knot_py"), cc = TempDir("knot_cc");
    fs::copy_file(script, py / "gen_knot.py");
    ChildRun r = RunChild({"python3", (py / "gen_knot.py").string(), "50", "10"});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    WriteKnotScene(cc.string(), 50, 10, true);
    EXPECT_EQ(ReadFile(py / "knot.pbrt"), ReadFile(cc / "knot.pbrt"));
    EXPECT_EQ(ReadFile(py / "knot.ply"), ReadFile(cc / "knot.ply"));
    EXPECT_EQ(ReadFile(py / "knot.pov"), ReadFile(cc / "knot.pov"));
    EXPECT_EQ(ReadFile(py / "knot_mesh.inc"), ReadFile(cc / "knot_mesh.inc"));
}

TEST(Ceiling, InProcessBothTraversals) {
    fs::path dir = TempDir("ceiling");
    KnotFiles kf = WriteKnotScene(dir.string(), 60, 10, false);
    for (CeilingTraversal t : {CeilingTraversal::Single, CeilingTraversal::Packet16}) {
        CeilingOptions o;
        o.scene = kf.pbrt;
        o.width = 40;
        o.height = 30;
        o.repeats = 2;
        o.traversal = t;
        CeilingResult r = RunCeiling(o, nullptr);
        ASSERT_EQ(r.repeats.size(), 2u);
        // Both passes trace the same camera rays; with one point light and matte surfaces
        // the render traces at most one shadow ray per hit, like the ceiling.
        for (const CeilingRepeat &rep : r.repeats) {
            EXPECT_GE(rep.ceilingRays, 1200u);
            EXPECT_GE(rep.renderRays, 1200u);
            EXPECT_LE(rep.renderRays, rep.ceilingRays);
        }
        EXPECT_GT(r.hitFraction, 0.3);
        EXPECT_GT(r.Ratio(), 0);
    }
}

TEST(Ceiling, CommandLastLine) {
    fs::path dir = TempDir("ceiling_cmd");
    KnotFiles kf = WriteKnotScene(dir.string(), 60, 10, false);
    ChildRun r = RunChild({PRISM_BINARY, "bench", "ceiling", kf.pbrt, "--res", "48x36", "--repeats",
                           "3", "--threads", "2"});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    std::string out = r.out;
    while (!out.empty() && out.back() == '\n') out.pop_back();
    std::string last = out.substr(out.rfind('\n') + 1);
    std::smatch m;
    ASSERT_TRUE(std::regex_match(
        last, m,
        std::regex(
            R"(ceiling ([0-9]+\.[0-9]{2}) Mrays/s, render ([0-9]+\.[0-9]{2}) Mrays/s, ratio ([0-9]+\.[0-9]{2}))")))
        << last;
    EXPECT_GT(std::stod(m[3].str()), 0);
    EXPECT_NE(out.find("repeat 3:"), std::string::npos);
}

TEST(Ceiling, BadSceneIsUsageError) {
    ChildRun r = RunChild({PRISM_BINARY, "bench", "ceiling", "/nonexistent/scene.pbrt"});
    EXPECT_EQ(r.exitStatus, 2);
    EXPECT_FALSE(r.err.empty());
}

TEST(Suite, ParsesPrismAndPovStatistics) {
    PrismRenderStats s = ParsePrismStats(
        "x.png: 800x600, 1 spp, maxdepth 5, double precision\n"
        "time: parse 0.012s, setup 0.003s, BVH build 0.020s, render 0.260s\n"
        "rays: camera 480000, shadow 10, reflection 0, refraction 0, pass-through 0; 3.75 "
        "Mrays/s\n");
    EXPECT_DOUBLE_EQ(s.parse, 0.012);
    EXPECT_DOUBLE_EQ(s.setup, 0.003);
    EXPECT_DOUBLE_EQ(s.bvh, 0.020);
    EXPECT_DOUBLE_EQ(s.render, 0.260);
    EXPECT_DOUBLE_EQ(s.mrays, 3.75);
    EXPECT_LT(ParsePrismStats("nothing").render, 0);
    std::string pov =
        "Parser Time\n  Parse Time:       0 hours  0 minutes  0 seconds (0.001 seconds)\n"
        "  Trace Time:       0 hours  0 minutes  1 seconds (1.170 seconds)\n";
    EXPECT_DOUBLE_EQ(ParsePovTime(pov, "Trace Time"), 1.170);
    EXPECT_DOUBLE_EQ(ParsePovTime(pov, "Parse Time"), 0.001);
    EXPECT_LT(ParsePovTime(pov, "Photon Time"), 0);
}

TEST(Suite, TargetsAndCsv) {
    EXPECT_EQ(TargetStatus(0.8, ">= 0.75"), "met");
    EXPECT_EQ(TargetStatus(0.7, ">= 0.75"), "missed");
    EXPECT_EQ(TargetStatus(29, "< 30"), "met");
    EXPECT_EQ(TargetStatus(30, "< 30"), "missed");
    EXPECT_EQ(TargetStatus(100, "<= 100"), "met");
    std::string csv = MetricsCsv({{"startup", "prism --help", 12.5, "ms", "< 30", "met"}});
    EXPECT_EQ(csv,
              "section,metric,value,unit,target,status\nstartup,prism --help,12.5,ms,< 30,met\n");
}

TEST(Suite, ChildRusageAndOutput) {
    ChildRun r = RunChild({"sh", "-c", "echo out; echo err >&2; exit 3"});
    EXPECT_EQ(r.exitStatus, 3);
    EXPECT_EQ(r.out, "out\n");
    EXPECT_EQ(r.err, "err\n");
    EXPECT_GT(r.maxRssKiB, 0);
    EXPECT_GT(r.wallSeconds, 0);
    EXPECT_THROW(RunChild({"/nonexistent/program"}), std::runtime_error);
    EXPECT_TRUE(OnPath("sh"));
    EXPECT_FALSE(OnPath("no-such-program-prism"));
}

}  // namespace
}  // namespace prism
