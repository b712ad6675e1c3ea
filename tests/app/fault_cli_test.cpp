// The faults a render farm sees (issue 17), each with a clear message and nothing lost: a
// missing or read-only output folder, a full disk while the image is written, a scene file cut
// short while it is read, a batch render killed by SIGKILL (the OOM killer's signal), and a
// --max-memory smaller than the scene. The full disk and the cut-short file are made by a real
// small tmpfs where this machine lets the test mount one, and always by the LD_PRELOAD library
// fault_shim/fault_shim.cpp (built with the tests), which also kills the batch's render.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "support/process.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

const std::string kScene = std::string(kCliHead) + "Shape \"sphere\"\n";

// The environment that preloads the fault library with `faults` ("NAME=value ..."). The
// sanitizer build's processes accept a preloaded library before the ASan runtime only with
// verify_asan_link_order=0.
std::string Faults(const std::string &faults) {
    return "ASAN_OPTIONS=\"${ASAN_OPTIONS}:verify_asan_link_order=0\" LD_PRELOAD='" +
           std::string(PRISM_FAULT_SHIM) + "' " + faults;
}

// A tmpfs mounted at `dir` for the life of the object, when this process may mount one
// (root with CAP_SYS_ADMIN, as in this container); Mounted() says whether it is.
class Tmpfs {
  public:
    Tmpfs(const fs::path &dir, const std::string &options) : dir_(dir) {
        std::string cmd =
            "mount -t tmpfs -o " + options + " prism-test '" + dir.string() + "' >/dev/null 2>&1";
        mounted_ = ::geteuid() == 0 && std::system(cmd.c_str()) == 0;
    }
    ~Tmpfs() {
        if (mounted_) std::system(("umount '" + dir_.string() + "' >/dev/null 2>&1").c_str());
    }
    bool Mounted() const { return mounted_; }

  private:
    fs::path dir_;
    bool mounted_ = false;
};

// Files in `dir` other than `keep`: temporary files left behind.
int OtherFiles(const fs::path &dir, const std::string &keep) {
    int n = 0;
    for (const auto &e : fs::directory_iterator(dir))
        if (e.path().filename() != keep) ++n;
    return n;
}

TEST(Faults, MissingOutputFolderIsRefusedBeforeRendering) {
    fs::path dir = TempDir("missing");
    std::ofstream(dir / "s.pbrt") << kScene;
    RunResult r = RunPrism("render s.pbrt -o nowhere/out.png -q", dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("output directory \"nowhere\" does not exist"), std::string::npos)
        << r.err;
}

TEST(Faults, ReadOnlyOutputFolderIsRefusedBeforeRendering) {
    fs::path dir = TempDir("readonly");
    std::ofstream(dir / "s.pbrt") << kScene;
    fs::create_directories(dir / "ro");
    std::optional<Tmpfs> roMount;
    if (::geteuid() == 0) {
        // chmod does not stop root: mount a read-only file system there instead.
        roMount.emplace(dir / "ro", "ro,size=64k");
        if (!roMount->Mounted())
            GTEST_SKIP() << "running as root, where chmod does not stop writes, and a "
                            "read-only tmpfs cannot be mounted here";
    } else {
        fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);
    }
    RunResult r = RunPrism("render s.pbrt -o ro/out.png -q", dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("cannot write to output directory \"ro\""), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("render:"), std::string::npos);  // refused before rendering
    std::ofstream(dir / "s.pbrt.list") << "s.pbrt\n";
    RunResult b = RunPrism("batch s.pbrt.list -o ro -q", dir);
    EXPECT_EQ(b.exitCode, 2) << b.err;
    EXPECT_NE(b.err.find("cannot write to output directory \"ro\""), std::string::npos) << b.err;
    EXPECT_TRUE(fs::is_empty(dir / "ro"));
    if (!roMount) fs::permissions(dir / "ro", fs::perms::owner_all);
}

// Disk full while the image is written: the error names the cause, the temporary file is
// removed and the previous image stays as it was.
void ExpectDiskFullKeepsOldImage(const fs::path &dir, const fs::path &outDir,
                                 const std::string &env, const std::string &format) {
    const std::string name = "out." + format;
    const std::string old = "the previous image";
    std::ofstream(outDir / name) << old;
    RunResult r =
        RunPrism("render s.pbrt --res 64x64 -o '" + (outDir / name).string() + "' -q", dir, env);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("cannot write image"), std::string::npos) << r.err;
    EXPECT_EQ(ReadFile(outDir / name), old);
    EXPECT_EQ(OtherFiles(outDir, name) - (fs::exists(outDir / "filler") ? 1 : 0), 0);
}

// Every format Prism writes (issue 25: TGA and BMP exited 0 with an empty file in place of the
// old one, JPEG exited from inside libjpeg leaving its temporary file).
const char *const kOutputFormats[] = {"png", "exr", "pfm", "hdr", "tga", "bmp", "jpg", "jpeg"};

TEST(Faults, DiskFullWhileWritingKeepsTheOldImage) {
    fs::path dir = TempDir("full");
    std::ofstream(dir / "s.pbrt") << kScene;
    // The LD_PRELOAD library: writes fail with ENOSPC after 100 bytes.
    for (const char *fmt : kOutputFormats) {
        const std::string format = fmt;
        SCOPED_TRACE(format);
        fs::create_directories(dir / format);
        ExpectDiskFullKeepsOldImage(dir, dir / format, Faults("PRISM_FAULT_ENOSPC_AFTER=100"),
                                    format);
    }
    // A real full file system, where a tmpfs can be mounted: one folder per format, each with
    // its previous image, then filled up.
    fs::create_directories(dir / "tmpfs");
    Tmpfs full(dir / "tmpfs", "size=256k");
    if (!full.Mounted()) return;
    for (const char *fmt : kOutputFormats) {
        fs::create_directories(dir / "tmpfs" / fmt);
        std::ofstream(dir / "tmpfs" / fmt / ("out." + std::string(fmt))) << "the previous image";
    }
    {
        std::ofstream filler(dir / "tmpfs/filler", std::ios::binary);
        std::string block(4096, 'x');
        while (filler.write(block.data(), std::streamsize(block.size())) && filler.flush()) {
        }
    }
    for (const char *fmt : kOutputFormats) {
        SCOPED_TRACE(std::string("tmpfs ") + fmt);
        ExpectDiskFullKeepsOldImage(dir, dir / "tmpfs" / fmt, "", fmt);
    }
}

// A batch whose output disk fills up: renders that cannot write fail with the reason, reports
// that cannot be rewritten are warnings, and every image that was written stays complete.
TEST(Faults, BatchOnAFillingDiskKeepsWhatItWrote) {
    fs::path dir = TempDir("batchfull");
    fs::create_directories(dir / "in");
    for (int i = 0; i < 24; ++i) {
        std::string name = "s";  // built step by step: GCC 12 warns on "s" + std::string + ...
        name += std::to_string(100 + i);
        name += ".pbrt";
        std::ofstream(dir / "in" / name) << kScene;
    }
    fs::create_directories(dir / "out");
    Tmpfs full(dir / "out", "size=48k");
    if (!full.Mounted()) GTEST_SKIP() << "a tmpfs cannot be mounted here";
    RunResult r = RunPrism("batch in -o out --res 64x64 -q", dir);
    EXPECT_NE(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    int images = 0;
    for (const auto &e : fs::directory_iterator(dir / "out")) {
        std::string name = e.path().filename().string();
        EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
        if (e.path().extension() != ".png") continue;
        ++images;
        // A complete PNG ends with its IEND chunk.
        std::string png = ReadFile(e.path());
        ASSERT_GE(png.size(), 12u) << name;
        EXPECT_EQ(png.substr(png.size() - 8, 4), "IEND") << name;
    }
    EXPECT_GT(images, 0);
    EXPECT_LT(images, 24);
    EXPECT_TRUE(fs::exists(dir / "out/report.json"));
}

TEST(Faults, SceneFileCutShortWhileReadIsAnError) {
    fs::path dir = TempDir("truncated");
    std::ofstream(dir / "s.pbrt") << kScene;
    RunResult r =
        RunPrism("render s.pbrt -o out.png -q", dir, Faults("PRISM_FAULT_TRUNCATE=s.pbrt"));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("s.pbrt: error: cannot open file \"s.pbrt\": the file changed while it "
                         "was read"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    // An included file: the error points at the Include.
    std::ofstream(dir / "part.pbrt") << "Shape \"sphere\" \"float radius\" 0.5\n";
    std::ofstream(dir / "t.pbrt") << kScene << "Include \"part.pbrt\"\n";
    r = RunPrism("render t.pbrt -o out.png -q", dir, Faults("PRISM_FAULT_TRUNCATE=part.pbrt"));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("t.pbrt:7:1: error: cannot open file \"part.pbrt\": the file changed"),
              std::string::npos)
        << r.err;
}

TEST(Faults, BatchReportsARenderKilledBySigkillAndGoesOn) {
    fs::path dir = TempDir("killed");
    fs::create_directories(dir / "in");
    for (const char *name : {"a.pbrt", "killme.pbrt", "c.pbrt"})
        std::ofstream(dir / "in" / name) << kScene;
    RunResult r = RunPrism("batch in -o out -q", dir, Faults("PRISM_FAULT_KILL=killme"));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    std::string report = ReadFile(dir / "out/report.json");
    size_t at = report.find("killme.pbrt");
    ASSERT_NE(at, std::string::npos) << report;
    std::string line = report.substr(at, report.find('\n', at) - at);
    EXPECT_NE(line.find("\"status\": \"failed\""), std::string::npos) << line;
    EXPECT_NE(line.find("\"exit_code\": 137"), std::string::npos) << line;
    EXPECT_NE(line.find("killed by signal SIGKILL"), std::string::npos) << line;
    EXPECT_TRUE(fs::exists(dir / "out/in_a.png")) << report;
    EXPECT_TRUE(fs::exists(dir / "out/in_c.png")) << report;
    EXPECT_FALSE(fs::exists(dir / "out/in_killme.png"));
    for (const auto &e : fs::directory_iterator(dir / "out"))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
    EXPECT_NE(ReadFile(dir / "out/summary.txt").find("SIGKILL"), std::string::npos);
}

TEST(Faults, MaxMemorySmallerThanTheSceneIsRefusedBeforeWork) {
    fs::path dir = TempDir("memory");
    std::ofstream(dir / "s.pbrt") << kScene;
    for (const char *cmd :
         {"render s.pbrt -o out.png -q", "info s.pbrt", "validate s.pbrt --out v -q"}) {
        SCOPED_TRACE(cmd);
        RunResult r = RunPrism(std::string(cmd) + " --max-memory 1K", dir);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find("memory budget of 1.0 KiB (--max-memory)"), std::string::npos)
            << r.err;
        EXPECT_EQ(r.err.find("render:"), std::string::npos);
        EXPECT_FALSE(fs::exists(dir / "out.png"));
        EXPECT_TRUE(r.out.empty() || r.out.find("shapes:") == std::string::npos) << r.out;
    }
}

}  // namespace
}  // namespace prism
