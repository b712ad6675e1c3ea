// prism-mpi under mpirun (oversubscribed on this machine): images bit-identical to `prism
// render`, a batch whose report matches `prism batch`'s, failures reported, a dead rank.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <thread>

#include "support/process.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism::test {
namespace {

// mpirun as CI runs it: oversubscribed (the ranks share this machine's cores), as root when
// the tests run as root, without binding (the ranks' TBB threads may use every core) and
// without probing network interfaces other than loopback.
std::string Mpirun(int np) {
    std::string cmd =
        "OMPI_MCA_btl_tcp_if_include=lo OMPI_MCA_oob_tcp_if_include=lo "
        "OMPI_MCA_btl=self,vader,tcp OMPI_MCA_pml=ob1 "
        "OMPI_MCA_rmaps_base_oversubscribe=1 '" +
        std::string(PRISM_MPIEXEC) + "' --oversubscribe --bind-to none";
    if (geteuid() == 0) cmd += " --allow-run-as-root";
    return cmd + " -np " + std::to_string(np) + " '" + PRISM_MPI_BINARY + "' ";
}

RunResult RunShell(const std::string &cmd, const fs::path &cwd) {
    fs::path outFile = cwd / "mpi_stdout.txt", errFile = cwd / "mpi_stderr.txt";
    std::string full = "cd '" + cwd.string() + "' && " + cmd + " >'" + outFile.string() + "' 2>'" +
                       errFile.string() + "' </dev/null";
    int status = std::system(full.c_str());
    RunResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = ReadFile(outFile);
    r.err = ReadFile(errFile);
    return r;
}

RunResult RunMpi(int np, const std::string &args, const fs::path &cwd) {
    return RunShell(Mpirun(np) + args, cwd);
}

class MpiTest : public FreshDirTest {};

// Renders `scene` with prism and with prism-mpi at -np 2 and 3 and compares the EXR files'
// bytes (the pixels are float: any difference in the sums would show).
void ExpectBitIdentical(const fs::path &dir, const std::string &scene, const std::string &opts) {
    RunResult single = RunPrism("render '" + scene + "' -o single.exr --quiet " + opts, dir);
    ASSERT_EQ(single.exitCode, 0) << single.err;
    const std::string want = ReadFile(dir / "single.exr");
    ASSERT_FALSE(want.empty());
    for (int np : {2, 3}) {
        std::string out = "mpi" + std::to_string(np) + ".exr";
        RunResult r = RunMpi(np, "render '" + scene + "' -o " + out + " --quiet " + opts, dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_TRUE(ReadFile(dir / out) == want) << scene << " differs at -np " << np;
    }
}

TEST_F(MpiTest, RenderIsBitIdenticalForQuadricsPbrt) {
    // The box filter's footprints overlap by a pixel, so the merge order matters already.
    ExpectBitIdentical(dir_, test::Source + "/scenes/quadrics.pbrt", "--res 72x40 --spp 2");
}

TEST_F(MpiTest, RenderIsBitIdenticalWithGaussianFilterAndGlossyRays) {
    // Footprints 4 pixels wider than the tiles; the distribution integrator's glossy rays.
    ExpectBitIdentical(dir_, test::Source + "/scenes/distribution.pbrt", "--res 40x24 --spp 1");
}

TEST_F(MpiTest, RenderIsBitIdenticalWithBdptSplats) {
    // Light tracing's splats land on other ranks' tiles: they travel with the tile sums.
    ExpectBitIdentical(dir_, test::Source + "/scenes/bdpt-gap.pbrt", "--res 40x30 --spp 2");
}

TEST_F(MpiTest, TargetErrorIsRefusedOnce) {
    std::string scene = test::Source + "/scenes/quadrics.pbrt";
    RunResult r = RunMpi(2, "render '" + scene + "' -o t.png --target-error 0.1", dir_);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    size_t first = r.err.find("--target-error");
    ASSERT_NE(first, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("does not take", first + 1), std::string::npos) << r.err;
}

TEST_F(MpiTest, RenderIsBitIdenticalForObj) {
    fs::path scene =
        fs::path(PRISM_SHARED_DIR) / "scenes/obj-cornellbox-original/CornellBox-Original.obj";
    PRISM_REQUIRE_SHARED(scene);
    ExpectBitIdentical(dir_, scene.string(), "--res 48x40 --spp 1");
}

TEST_F(MpiTest, RenderIsBitIdenticalForGltf) {
    fs::path scene = fs::path(PRISM_SHARED_DIR) / "scenes/gltf-duck/Duck.gltf";
    PRISM_REQUIRE_SHARED(scene);
    ExpectBitIdentical(dir_, scene.string(), "--res 40x40 --spp 1");
}

TEST_F(MpiTest, RenderPrintsRankStatistics) {
    std::string scene = test::Source + "/scenes/quadrics.pbrt";
    RunResult r = RunMpi(3, "render '" + scene + "' -o q.png --res 64x32 --no-progress", dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("mpi: 3 ranks"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("mpi: rank 1:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("mpi: rank 2:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("rays: camera"), std::string::npos) << r.err;
}

TEST_F(MpiTest, BadSceneIsOneLocatedError) {
    WriteTestFile(dir_ / "bad.pbrt", "WorldBegin\nShape \"sphere\" \"float radius\" [ x ]\n");
    RunResult r = RunMpi(3, "render bad.pbrt -o bad.png", dir_);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    std::smatch m;
    EXPECT_TRUE(std::regex_search(r.err, m, std::regex("bad\\.pbrt:2:\\d+: error"))) << r.err;
    // Printed once, by rank 0, although every rank loaded the scene.
    size_t first = r.err.find("bad.pbrt:2:");
    EXPECT_EQ(r.err.find("bad.pbrt:2:", first + 1), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad.png"));
}

std::string Sphere(int w, int h) {
    return "Film \"image\" \"integer xresolution\" " + std::to_string(w) +
           " \"integer yresolution\" " + std::to_string(h) +
           "\nSampler \"halton\" \"integer pixelsamples\" 1\n"
           "LookAt 0 0 -4 0 0 0 0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
           "WorldBegin\nLightSource \"point\" \"point from\" [0 3 -3] \"rgb I\" [20 20 20]\n"
           "Material \"matte\"\nShape \"sphere\"\nWorldEnd\n";
}

// report.json without what differs from run to run: timings, memory and ranks.
std::string StableReport(const fs::path &outDir) {
    std::string s = ReadFile(outDir / "report.json");
    s = std::regex_replace(s,
                           std::regex("\"(seconds|end_seconds|wall_seconds|render_seconds|"
                                      "parse|setup|bvh|render|peak_rss_kib|rank)\": [0-9.]+"),
                           "\"$1\": _");
    s = std::regex_replace(s, std::regex("\"rank\": _, "), "");
    return s;
}

TEST_F(MpiTest, BatchReportMatchesSingleProcessAndFailuresAreReported) {
    fs::create_directories(dir_ / "in");
    for (int k = 0; k < 5; ++k)
        WriteTestFile(dir_ / "in" / ("s" + std::to_string(k) + ".pbrt"), Sphere(16 + 4 * k, 12));
    WriteTestFile(dir_ / "in/broken.pbrt", "Camera \"perspective\"\nWorldBegin\nSphere 1\n");
    RunResult single = RunPrism("batch in -o single --quiet", dir_);
    EXPECT_EQ(single.exitCode, 2) << single.err;
    for (int np : {2, 3}) {
        std::string out = "mpi" + std::to_string(np);
        RunResult r = RunMpi(np, "batch in -o " + out + " --quiet", dir_);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        std::string report = ReadFile(dir_ / out / "report.json");
        EXPECT_NE(report.find("\"rank\": 1"), std::string::npos) << report;
        // The same report apart from timings and ranks; the output names differ only in the
        // folder.
        std::string want =
            std::regex_replace(StableReport(dir_ / "single"), std::regex("single/"), out + "/");
        EXPECT_EQ(StableReport(dir_ / out), want);
        EXPECT_NE(report.find("unknown directive"), std::string::npos) << report;
        for (int k = 0; k < 5; ++k)
            EXPECT_EQ(ReadFile(dir_ / out / ("in_s" + std::to_string(k) + ".png")),
                      ReadFile(dir_ / "single" / ("in_s" + std::to_string(k) + ".png")));
        EXPECT_TRUE(fs::exists(dir_ / out / "summary.txt"));
    }
}

// The pid of the prism-mpi process of rank `rank` running in `cwd` (from /proc: Open MPI sets
// OMPI_COMM_WORLD_RANK in each rank's environment), or -1.
pid_t FindRank(int rank, const fs::path &cwd) {
    const std::string want = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
    for (const auto &e : fs::directory_iterator("/proc")) {
        std::string name = e.path().filename();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        std::error_code ec;
        if (fs::read_symlink(e.path() / "exe", ec).filename() != "prism-mpi" || ec) continue;
        if (fs::read_symlink(e.path() / "cwd", ec) != cwd || ec) continue;
        std::string env = ReadFile(e.path() / "environ");
        if (env.find(std::string(1, '\0') + want + std::string(1, '\0')) != std::string::npos ||
            env.rfind(want + std::string(1, '\0'), 0) == 0)
            return pid_t(std::stoi(name));
    }
    return -1;
}

TEST_F(MpiTest, KilledRankEndsTheBatchAndKeepsFinishedImages) {
    fs::create_directories(dir_ / "in");
    // Quick scenes first, then slow ones, so some finish before the kill and some do not.
    for (int k = 0; k < 3; ++k)
        WriteTestFile(dir_ / "in" / ("a" + std::to_string(k) + ".pbrt"), Sphere(16, 12));
    for (int k = 0; k < 6; ++k)
        WriteTestFile(dir_ / "in" / ("b" + std::to_string(k) + ".pbrt"), Sphere(640, 480));
    // Runs in the background; the test kills rank 2 once a scene is finished.
    std::string cmd = "cd '" + dir_.string() + "' && (" + Mpirun(3) +
                      "batch in -o out --spp 64 --threads 1; echo $? >rc.txt) >mpi_stdout.txt "
                      "2>mpi_stderr.txt </dev/null &";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    pid_t victim = -1;
    while (std::chrono::steady_clock::now() < deadline) {
        std::string report = ReadFile(dir_ / "out/report.json");
        if (report.find("\"status\": \"ok\"") != std::string::npos &&
            report.find("\"status\": \"running\"") != std::string::npos)
            if ((victim = FindRank(2, fs::canonical(dir_))) > 0) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ASSERT_GT(victim, 0) << "no finished scene or no rank 2 within 60 s";
    const pid_t other = FindRank(1, fs::canonical(dir_));
    kill(victim, SIGKILL);
    while (!fs::exists(dir_ / "rc.txt") &&
           std::chrono::steady_clock::now() < deadline + std::chrono::seconds(60))
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_TRUE(fs::exists(dir_ / "rc.txt"));
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    std::string err = ReadFile(dir_ / "mpi_stderr.txt");
    EXPECT_NE(std::stoi(ReadFile(dir_ / "rc.txt")), 0);
    // mpirun names the rank (rank 0's own line may be cut off: docs/DISTRIBUTED.md).
    EXPECT_TRUE(std::regex_search(err, std::regex("process rank 2 .*signal 9"))) << err;
    // Every scene the report calls finished has its image.
    std::string report = ReadFile(dir_ / "out/report.json");
    std::regex okLine("\"output\": \"([^\"]+)\", \"status\": \"ok\"");
    int ok = 0;
    for (auto it = std::sregex_iterator(report.begin(), report.end(), okLine);
         it != std::sregex_iterator(); ++it, ++ok)
        EXPECT_TRUE(fs::exists(dir_ / (*it)[1].str())) << (*it)[1].str();
    EXPECT_GE(ok, 1) << report;
    // No half-written file is left behind: the renders' logs are in the temporary folder.
    for (const auto &e : fs::directory_iterator(dir_ / "out"))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
    // The logs of the renders the job cut short (`.prism-<rank pid>-XXXXXX.log.tmp`).
    for (const auto &e : fs::directory_iterator(fs::temp_directory_path())) {
        std::string name = e.path().filename();
        for (pid_t p : {victim, other})
            if (name.rfind(".prism-" + std::to_string(p) + "-", 0) == 0 && name.size() > 8 &&
                name.compare(name.size() - 8, 8, ".log.tmp") == 0)
                fs::remove(e.path());
    }
}

// The render logs a batch's ranks keep in the node's temporary folder had guessable names
// (`prism-mpi-<pid>-<index>.log`): another user of /tmp could plant a link or a file there
// first. They are created as every temporary is (CreateUniqueFile: a random suffix,
// O_EXCL | O_NOFOLLOW), and removed once read.
TEST_F(MpiTest, BatchRenderLogsHaveUnguessableNames) {
    fs::create_directories(dir_ / "in");
    fs::create_directories(dir_ / "tmp");
    for (int k = 0; k < 4; ++k)
        WriteTestFile(dir_ / "in" / ("s" + std::to_string(k) + ".pbrt"), Sphere(320, 240));
    std::string cmd = "cd '" + dir_.string() + "' && (TMPDIR='" + (dir_ / "tmp").string() + "' " +
                      Mpirun(2) +
                      "batch in -o out --spp 16 --threads 1 --quiet; echo $? >rc.txt) "
                      ">mpi_stdout.txt 2>mpi_stderr.txt </dev/null &";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    std::set<std::string> seen;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(dir_ / "rc.txt") && std::chrono::steady_clock::now() < deadline) {
        std::error_code ec;
        for (const auto &e : fs::directory_iterator(dir_ / "tmp", ec))
            if (e.path().filename().string().find("prism") != std::string::npos)  // not Open MPI's
                seen.insert(e.path().filename().string());
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_TRUE(fs::exists(dir_ / "rc.txt")) << ReadFile(dir_ / "mpi_stderr.txt");
    EXPECT_EQ(std::stoi(ReadFile(dir_ / "rc.txt")), 0) << ReadFile(dir_ / "mpi_stderr.txt");
    EXPECT_FALSE(seen.empty());
    const std::regex unique(R"(\.prism-[0-9]+-[A-Za-z0-9]{6}\.log\.tmp)");
    for (const std::string &name : seen) EXPECT_TRUE(std::regex_match(name, unique)) << name;
    for (const auto &e : fs::directory_iterator(dir_ / "tmp"))  // every log removed
        EXPECT_EQ(e.path().filename().string().find("prism"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace prism::test
