// Hostile scenes, round two (issue 25): small files that make Prism recurse too deep (stack
// overflow), do quadratic work in its diagnostics, or print bytes that corrupt a terminal or a
// report. The files are generated here: most are too large to check in, and their point is
// their size. Each case must end with one located error (or the documented cap) and exit 2,
// never a signal.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "app/run_prism.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using test::ReadFile;
using test::RunPrism;
using test::RunResult;

fs::path TempDir(const std::string &name) { return test::FreshTempDir("hostile", name); }

// Five lines; what a case adds starts on line 6.
const char *const kHead =
    "LookAt 0 0 5  0 0 0  0 1 0\n"
    "Camera \"perspective\" \"float fov\" 40\n"
    "Film \"image\" \"integer xresolution\" 8 \"integer yresolution\" 8\n"
    "WorldBegin\n"
    "LightSource \"point\" \"rgb I\" [10 10 10] \"point from\" [0 0 5]\n";

int ErrorLines(const std::string &err) {
    int n = 0;
    for (size_t at = err.find("error:"); at != std::string::npos; at = err.find("error:", at + 1))
        ++n;
    return n;
}

// Renders `scene` in `dir`: exit status 2, exactly one error line containing `fragment`,
// nothing written.
void ExpectRefused(const fs::path &dir, const std::string &scene, const std::string &fragment,
                   const std::string &command = "render") {
    SCOPED_TRACE(command + " " + scene);
    const std::string args = command == "render" ? " -o out.png -q" : "";
    RunResult r = RunPrism(command + " " + scene + args, dir, "timeout -k 5 120");
    EXPECT_EQ(r.exitCode, 2) << r.err.substr(0, 2000);
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err.substr(0, 2000);
    EXPECT_EQ(ErrorLines(r.err), 1) << r.err.substr(0, 2000);
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

void ExpectRenders(const fs::path &dir, const std::string &scene) {
    SCOPED_TRACE(scene);
    RunResult r = RunPrism("render " + scene + " -o ok.png -q", dir, "timeout -k 5 120");
    EXPECT_EQ(r.exitCode, 0) << r.err.substr(0, 2000);
    fs::remove(dir / "ok.png");
}

// A glTF with no geometry whose asset "extras" nest `depth` levels, alternating arrays and
// objects; the deepest bracket is on line 2.
std::string NestedGltf(int depth) {
    std::string open, close;
    for (int i = 0; i < depth; ++i) {
        open += i % 2 ? "{\"a\": " : "[";
        close.insert(0, i % 2 ? "}" : "]");
    }
    return "{\"asset\": {\"version\": \"2.0\", \"extras\":\n" + open + "1" + close +
           "},\n\"scenes\": [{\"nodes\": []}], \"nodes\": [], \"note\": \"[[[[ {{{{\"}\n";
}

// The same JSON as a .glb (one JSON chunk, padded to 4 bytes).
std::string Glb(std::string json) {
    while (json.size() % 4) json += ' ';
    auto u32 = [](uint32_t v) {
        std::string s(4, '\0');
        for (int i = 0; i < 4; ++i) s[size_t(i)] = char((v >> (8 * i)) & 0xff);
        return s;
    };
    return "glTF" + u32(2) + u32(uint32_t(20 + json.size())) + u32(uint32_t(json.size())) + "JSON" +
           json;
}

TEST(Hostile, DeeplyNestedGltfJsonIsRefusedWithItsLocation) {
    fs::path dir = TempDir("gltf_depth");
    // 2 levels of the document itself + 510 of extras = 512: allowed.
    std::ofstream(dir / "ok.gltf") << NestedGltf(510);
    ExpectRenders(dir, "ok.gltf");
    std::ofstream(dir / "deep.gltf") << NestedGltf(20000);
    // The 513th bracket: 511 of the extras, at column 1 + 510 brackets ("[" and "{\"a\": ").
    std::ofstream(dir / "edge.gltf") << NestedGltf(511);
    for (const char *command : {"render", "info", "validate"}) {
        ExpectRefused(dir, "deep.gltf", "deep.gltf:2:", command);
        ExpectRefused(dir, "deep.gltf", "JSON arrays and objects nest deeper than 512 levels",
                      command);
    }
    ExpectRefused(dir, "edge.gltf", "edge.gltf:2:" + std::to_string(1 + 255 * 7) + ":");
    std::ofstream(dir / "deep.glb", std::ios::binary) << Glb(NestedGltf(20000));
    ExpectRefused(dir, "deep.glb", "deep.glb: error: JSON arrays and objects nest deeper");
}

// CSGBegin "union" `depth` times, each with a sphere beside the nested node.
std::string NestedCsg(int depth) {
    std::string s = kHead;
    for (int i = 0; i < depth; ++i)
        s += "CSGBegin \"union\"\nShape \"sphere\" \"float radius\" 0.5\n";
    for (int i = 0; i < depth; ++i) s += "CSGEnd\n";
    return s;
}

TEST(Hostile, DeeplyNestedCsgIsRefusedAtTheCsgBegin) {
    fs::path dir = TempDir("csg_depth");
    std::ofstream(dir / "ok.pbrt") << NestedCsg(256);
    ExpectRenders(dir, "ok.pbrt");
    std::ofstream(dir / "deep.pbrt") << NestedCsg(10000);
    // The 257th CSGBegin: line 6 + 2 * 256.
    ExpectRefused(dir, "deep.pbrt",
                  "deep.pbrt:518:1: error: CSG nodes nest more than 256 levels deep (outermost "
                  "CSGBegin at deep.pbrt:6:1)");
}

// `n` textures, each scaling the one before (twice: `twice`), and a sphere using the last.
std::string TextureChain(int n, bool twice) {
    std::string s = kHead;
    s += "Texture \"t0\" \"spectrum\" \"constant\" \"rgb value\" [0.5 0.5 0.5]\n";
    for (int i = 1; i < n; ++i) {
        std::string prev = "\"t" + std::to_string(i - 1) + "\"";
        s += "Texture \"t" + std::to_string(i) + "\" \"spectrum\" \"scale\" \"texture tex1\" " +
             prev + (twice ? " \"texture tex2\" " + prev : " \"rgb tex2\" [1 1 1]") + "\n";
    }
    return s + "Material \"matte\" \"texture Kd\" \"t" + std::to_string(n - 1) +
           "\"\nShape \"sphere\"\n";
}

TEST(Hostile, LongTextureChainsAreRefusedAtTheTexture) {
    fs::path dir = TempDir("texture_depth");
    std::ofstream(dir / "ok.pbrt") << TextureChain(256, false);
    ExpectRenders(dir, "ok.pbrt");
    std::ofstream(dir / "chain.pbrt") << TextureChain(100000, false);
    // t256 is the 257th texture, on line 6 + 256.
    ExpectRefused(dir, "chain.pbrt",
                  "chain.pbrt:262:1: error: texture \"t256\": textures refer to textures more "
                  "than 256 levels deep");
    // Each texture twice refers to the one before: t16 would evaluate 2^17 - 1 textures.
    std::ofstream(dir / "twice.pbrt") << TextureChain(40, true);
    ExpectRefused(dir, "twice.pbrt",
                  "twice.pbrt:22:1: error: texture \"t16\": one lookup would evaluate more than "
                  "65536 textures");
}

int WarningLines(const std::string &err) {
    int n = 0;
    for (size_t at = err.find("warning:"); at != std::string::npos;
         at = err.find("warning:", at + 1))
        ++n;
    return n;
}

// 40,000 warnings of one kind (issue 25: the de-duplication compared each new warning with
// every earlier one; 40,000 unused parameters took 66 s, 40,000 unclosed AttributeBegin over
// 60 s, and printed 40,000 lines): the first ten and one summary line. The test's timeout is
// the guard for the time; nothing here measures it.
TEST(Hostile, ManyWarningsOfOneKindPrintTenAndOneSummaryLine) {
    fs::path dir = TempDir("warnings");
    // Behind the camera: the spheres are never hit, so the render itself costs nothing.
    std::string unused = std::string(kHead) + "Translate 0 0 100\n";
    for (int i = 0; i < 40000; ++i)
        unused += "Shape \"sphere\" \"float bogus" + std::to_string(i) + "\" 1\n";
    std::ofstream(dir / "unused.pbrt") << unused;
    std::string unclosed = kHead;
    for (int i = 0; i < 40000; ++i) unclosed += "AttributeBegin\n";
    std::ofstream(dir / "unclosed.pbrt") << unclosed << "Shape \"sphere\"\n";
    for (auto [scene, first, summary] :
         {std::tuple{"unused.pbrt", "unused.pbrt:7:16: warning: unused parameter \"bogus0\"",
                     "warning: and 39,990 more warnings like: unused parameter \"bogus10\" "
                     "(shape \"sphere\")\n"},
          std::tuple{"unclosed.pbrt",
                     "unclosed.pbrt:6:1: warning: AttributeBegin without matching AttributeEnd",
                     "warning: and 39,990 more warnings like: AttributeBegin without matching "
                     "AttributeEnd\n"}}) {
        SCOPED_TRACE(scene);
        RunResult r = RunPrism(std::string("render ") + scene + " -o out.png --no-progress", dir,
                               "timeout -k 5 120");
        EXPECT_EQ(r.exitCode, 0) << r.err.substr(0, 2000);
        EXPECT_EQ(WarningLines(r.err), 11) << r.err.substr(0, 2000);
        EXPECT_NE(r.err.find(first), std::string::npos) << r.err.substr(0, 2000);
        EXPECT_NE(r.err.find(summary), std::string::npos) << r.err.substr(0, 2000);
    }
    // The batch's report keeps the same eleven.
    std::ofstream(dir / "list.txt") << "unused.pbrt\n";
    RunResult b = RunPrism("batch list.txt -o out -q", dir, "timeout -k 5 120");
    EXPECT_EQ(b.exitCode, 0) << b.err.substr(0, 2000);
    std::string report = ReadFile(dir / "out/report.json");
    EXPECT_EQ(WarningLines(report), 11) << report.substr(0, 2000);
    EXPECT_NE(report.find("and 39,990 more warnings like"), std::string::npos);
}

// True when `s` has a byte below 0x20 other than newline, or 0x7f: what a terminal acts on.
bool HasRawControlChars(const std::string &s) {
    return std::any_of(s.begin(), s.end(), [](char c) {
        unsigned char u = static_cast<unsigned char>(c);
        return (u < 0x20 && c != '\n') || u == 0x7f;
    });
}

// Names with a NUL or control characters (issue 25): a NUL in a quoted path cut the message
// short there, and an escape sequence in a name reached the terminal as it was.
TEST(Hostile, NulAndControlCharactersInNamesArePrintedEscaped) {
    fs::path dir = TempDir("control_chars");
    std::string nul = std::string(kHead) + "Include \"a" + std::string(1, '\0') + "b.pbrt\"\n";
    std::ofstream(dir / "nul.pbrt", std::ios::binary) << nul;
    RunResult r = RunPrism("render nul.pbrt -o out.png -q", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("nul.pbrt:6:1: error: cannot open file \"a\\x00b.pbrt\": No such file"),
              std::string::npos)
        << r.err;
    // Warnings and an error naming escape sequences (colour, window title, clear screen).
    std::ofstream(dir / "esc.pbrt") << kHead << "Shape \"sph\x1b[31mere\"\n"
                                    << "Shape \"sphere\" \"float bo\x1b]0;owned\x07gus\" 1\n";
    r = RunPrism("render esc.pbrt -o out.png --no-progress", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(HasRawControlChars(r.err)) << r.err;
    EXPECT_NE(r.err.find("esc.pbrt:6:1: warning: shape \"sph\\x1b[31mere\""), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("unused parameter \"bo\\x1b]0;owned\\x07gus\""), std::string::npos)
        << r.err;
    // The output's name from the Film, in the render's statistics line.
    std::string film = kHead;
    film.replace(film.find("Film \"image\""), 12,
                 "Film \"image\" \"string filename\" \"o\x1b[1mut.png\"");
    std::ofstream(dir / "film.pbrt") << film << "Shape \"sphere\"\n";
    r = RunPrism("render film.pbrt --no-progress", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(HasRawControlChars(r.err)) << r.err;
    EXPECT_NE(r.err.find("o\\x1b[1mut.png: 8x8"), std::string::npos) << r.err;
    std::ofstream(dir / "err.pbrt") << kHead << "NamedMaterial \"x\x1b[2J\"\n";
    r = RunPrism("render err.pbrt -o out.png", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_FALSE(HasRawControlChars(r.err)) << r.err;
    EXPECT_NE(r.err.find("err.pbrt:6:1: error: unknown named material \"x\\x1b[2J\""),
              std::string::npos)
        << r.err;
    EXPECT_EQ(ErrorLines(r.err), 1) << r.err;
}

// Whether `s` is well-formed UTF-8.
bool ValidUtf8(const std::string &s) {
    for (size_t i = 0; i < s.size();) {
        unsigned char b = static_cast<unsigned char>(s[i]);
        size_t n = b < 0x80                 ? 1
                   : b >= 0xc2 && b <= 0xdf ? 2
                   : b >= 0xe0 && b <= 0xef ? 3
                   : b >= 0xf0 && b <= 0xf4 ? 4
                                            : 0;
        if (n == 0 || i + n > s.size()) return false;
        for (size_t k = 1; k < n; ++k)
            if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return false;
        i += n;
    }
    return true;
}

// A batch over scene files whose names hold an escape sequence and a Latin-1 byte: summary.txt
// and the batch's stderr show them escaped, report.json stays valid UTF-8 (\u00XX).
TEST(Hostile, BatchReportsOfStrangeFileNamesAreEscaped) {
    fs::path dir = TempDir("batch_names");
    fs::create_directories(dir / "in");
    const std::string escName = "e\x1b[2Jvil.pbrt", latin1 = "caf\xe9.pbrt",
                      utf8 = "na\xc3\xafve.pbrt";
    for (const std::string &name : {escName, latin1, utf8})
        std::ofstream(dir / "in" / name) << kHead << "Shape \"sphere\"\n";
    std::ofstream(dir / "in" / "broken\x1b[1m.pbrt") << kHead << "Shape \"sph\x1b[5mere\" 1\n";
    RunResult r = RunPrism("batch in -o out", dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_FALSE(HasRawControlChars(r.err)) << r.err;
    std::string summary = ReadFile(dir / "out/summary.txt");
    EXPECT_FALSE(HasRawControlChars(summary)) << summary;
    EXPECT_NE(summary.find("in/e\\x1b[2Jvil.pbrt"), std::string::npos) << summary;
    std::string report = ReadFile(dir / "out/report.json");
    EXPECT_TRUE(ValidUtf8(report)) << report;
    EXPECT_FALSE(HasRawControlChars(report)) << report;
    EXPECT_NE(report.find("in/caf\\u00e9.pbrt"), std::string::npos) << report;
    EXPECT_NE(report.find("in/na\xc3\xafve.pbrt"), std::string::npos) << report;  // kept
    EXPECT_NE(report.find("in/e\\u001b[2Jvil.pbrt"), std::string::npos) << report;
}

// A legal 249-character output name (issue 25: the temporary name, the name plus about 20
// characters, went past the 255-byte limit of a file name).
TEST(Hostile, LongLegalOutputNamesAreWritten) {
    fs::path dir = TempDir("long_name");
    std::ofstream(dir / "s.pbrt") << kHead << "Shape \"sphere\"\n";
    for (const char *ext : {".png", ".exr"}) {
        const std::string name = std::string(249 - 4, 'n') + ext;
        RunResult r = RunPrism("render s.pbrt -o " + name + " -q", dir);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        EXPECT_TRUE(fs::exists(dir / name)) << ext;
    }
    // And a batch whose scene makes a 249-character image name (its render log is named apart).
    fs::create_directories(dir / "in");
    std::ofstream(dir / "in" / (std::string(249 - 8, 'b') + ".pbrt"))
        << kHead << "Shape \"sphere\"\n";
    RunResult r = RunPrism("batch in -o out -q", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err << ReadFile(dir / "out/report.json");
    EXPECT_TRUE(fs::exists(dir / "out" / ("in_" + std::string(249 - 8, 'b') + ".png")));
}

// A camera between two parallel mirrors, looking at one of them: every camera ray bounces
// `depth` times (Kr 1, so no ray is cut off), each pixel costs n * n * depth rays (n * n spp).
std::string MirrorHall(int w, int h, int n, int depth) {
    const std::string quad = "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n";
    return "LookAt 0 0 0  0 1 0  0 0 1\nCamera \"perspective\" \"float fov\" 1\n"
           "Film \"image\" \"integer xresolution\" " +
           std::to_string(w) + " \"integer yresolution\" " + std::to_string(h) +
           "\nSampler \"stratified\" \"integer xsamples\" " + std::to_string(n) +
           " \"integer ysamples\" " + std::to_string(n) +
           "\nIntegrator \"whitted\" \"integer maxdepth\" " + std::to_string(depth) +
           "\nWorldBegin\nLightSource \"point\" \"rgb I\" [1 1 1]\n"
           "Material \"mirror\" \"rgb Kr\" [1 1 1]\n" +
           quad + "  \"point3 P\" [-100 1 -100  100 1 -100  100 1 100  -100 1 100]\n" + quad +
           "  \"point3 P\" [-100 -1 -100  -100 -1 100  100 -1 100  100 -1 -100]\n";
}

// Forks `prism ARGS...` in dir with stderr to dir/err.txt; returns its pid.
pid_t Spawn(const fs::path &dir, const std::vector<std::string> &args) {
    pid_t pid = fork();
    if (pid == 0) {
        if (chdir(dir.c_str()) != 0) _exit(126);
        if (!std::freopen("err.txt", "w", stderr) || !std::freopen("/dev/null", "w", stdout))
            _exit(126);
        std::vector<char *> argv{const_cast<char *>(PRISM_BINARY)};
        for (const std::string &a : args) argv.push_back(const_cast<char *>(a.c_str()));
        argv.push_back(nullptr);
        execv(PRISM_BINARY, argv.data());
        _exit(127);
    }
    return pid;
}

// Waits up to `seconds` for pid; kills it (SIGKILL) if it is still running then. Returns its
// wait status, or -1 if it had to be killed.
int WaitOrKill(pid_t pid, int seconds) {
    int status = 0;
    for (int i = 0; i < seconds * 50; ++i) {
        if (waitpid(pid, &status, WNOHANG) == pid) return status;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    return -1;
}

// One 16x16 tile whose every camera packet (4x4 pixels) takes seconds: SIGINT used to be
// read only between tiles, so the render went on to the end of the tile (about a minute and
// a half here) before it stopped.
TEST(Hostile, InterruptStopsARenderInsideItsOnlyTile) {
    fs::path dir = TempDir("interrupt_tile");
    std::ofstream(dir / "hall.pbrt") << MirrorHall(16, 16, 40, 1000);
    pid_t pid = Spawn(dir, {"render", "hall.pbrt", "-o", "out.png", "-q", "--threads", "1"});
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::seconds(2));  // loaded (a few ms), rendering
    kill(pid, SIGINT);
    // A hang guard, not a timing: one packet takes a few seconds, the tile minutes.
    const int status = WaitOrKill(pid, 60);
    const std::string err = ReadFile(dir / "err.txt");
    ASSERT_NE(status, -1) << "the render went on after SIGINT: " << err;
    ASSERT_TRUE(WIFEXITED(status)) << err;
    EXPECT_EQ(WEXITSTATUS(status), 130) << err;
    EXPECT_NE(err.find("interrupted: no image written"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

// --time-limit used to let every started pass finish: a first pass of minutes ran to its end
// whatever the limit. The deadline now stops it within a camera packet; with no pass done
// there is no image.
TEST(Hostile, TimeLimitStopsAPassThatDoesNotFit) {
    fs::path dir = TempDir("time_limit_pass");
    std::ofstream(dir / "hall.pbrt") << MirrorHall(1024, 1024, 1, 1000);  // 2 spp: minutes
    RunResult r = RunPrism("render hall.pbrt -o out.png -q --threads 1 --time-limit 1", dir,
                           "timeout -k 5 60");
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("error: the time limit of 1s (--time-limit) ran out before the first "
                         "pass finished: no image written"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

// The pid of a child process of `parent` (from /proc/*/stat), or -1.
pid_t ChildOf(pid_t parent) {
    std::error_code ec;
    for (const auto &e : fs::directory_iterator("/proc", ec)) {
        const std::string name = e.path().filename().string();
        if (name.empty() || !std::all_of(name.begin(), name.end(), ::isdigit)) continue;
        const std::string stat = ReadFile(e.path() / "stat");
        const size_t close = stat.rfind(')');
        if (close == std::string::npos) continue;
        char state = 0;
        int ppid = 0;
        if (std::sscanf(stat.c_str() + close + 1, " %c %d", &state, &ppid) == 2 && ppid == parent)
            return pid_t(std::stoi(name));
    }
    return -1;
}

// Whether pid names a process that runs (not gone, not a zombie).
bool Runs(pid_t pid) {
    const std::string stat = ReadFile("/proc/" + std::to_string(pid) + "/stat");
    const size_t close = stat.rfind(')');
    if (close == std::string::npos) return false;
    char state = 0;
    return std::sscanf(stat.c_str() + close + 1, " %c", &state) == 1 && state != 'Z' &&
           state != 'X';
}

// Waits (up to a minute) for the render child of batch `pid`; -1 if none appeared.
pid_t WaitForRender(pid_t batch, const fs::path &dir, const std::string &scene) {
    for (int i = 0; i < 3000; ++i) {
        const pid_t child = ChildOf(batch);
        if (child > 0 && ReadFile("/proc/" + std::to_string(child) + "/cmdline").find(scene) !=
                             std::string::npos)
            return child;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ADD_FAILURE() << "no render of " << scene << " started: " << ReadFile(dir / "err.txt");
    return -1;
}

// report.json's entry for `scene` (its line), or "".
std::string ReportEntry(const fs::path &report, const std::string &scene) {
    const std::string json = ReadFile(report);
    const size_t at = json.find("{\"scene\": \"" + scene + "\"");
    return at == std::string::npos ? "" : json.substr(at, json.find('\n', at) - at);
}

// A batch had no time limit per scene: one scene that never finishes held the whole batch.
// --scene-timeout stops it (SIGTERM; the render stops within a camera packet), reports it
// "timeout" and renders the rest.
TEST(Hostile, BatchStopsASceneAtItsTimeoutAndGoesOn) {
    fs::path dir = TempDir("batch_timeout");
    std::ofstream(dir / "a.pbrt") << kHead << "Shape \"sphere\"\n";
    std::ofstream(dir / "hall.pbrt") << MirrorHall(256, 256, 8, 1000);  // an hour or so
    std::ofstream(dir / "c.pbrt") << kHead << "Shape \"sphere\"\n";
    std::ofstream(dir / "list.txt") << "a.pbrt\nhall.pbrt\nc.pbrt\n";
    RunResult r =
        RunPrism("batch list.txt -o out --threads 1 --scene-timeout 2", dir, "timeout -k 5 120");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    const fs::path report = dir / "out/report.json";
    EXPECT_NE(ReportEntry(report, "a.pbrt").find("\"status\": \"ok\""), std::string::npos)
        << ReadFile(report);
    const std::string hall = ReportEntry(report, "hall.pbrt");
    EXPECT_NE(hall.find("\"status\": \"timeout\""), std::string::npos) << ReadFile(report);
    EXPECT_NE(hall.find("render still running after 2 s (--scene-timeout): stopped with SIGTERM"),
              std::string::npos)
        << hall;
    EXPECT_NE(ReportEntry(report, "c.pbrt").find("\"status\": \"ok\""), std::string::npos)
        << ReadFile(report);
    EXPECT_NE(ReadFile(dir / "out/summary.txt").find("1 timed out"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir / "out/a.png"));
    EXPECT_TRUE(fs::exists(dir / "out/c.png"));
    EXPECT_FALSE(fs::exists(dir / "out/hall.png"));
}

// SIGKILL of `prism batch` (the OOM killer, a job scheduler) left its render running, an hour
// of a core and its memory, orphaned; the render now dies with the batch (PR_SET_PDEATHSIG).
TEST(Hostile, KillingTheBatchEndsItsRender) {
    fs::path dir = TempDir("batch_killed");
    std::ofstream(dir / "hall.pbrt") << MirrorHall(256, 256, 8, 1000);
    std::ofstream(dir / "list.txt") << "hall.pbrt\n";
    pid_t batch = Spawn(dir, {"batch", "list.txt", "-o", "out", "--threads", "1", "-q"});
    ASSERT_GT(batch, 0);
    const pid_t render = WaitForRender(batch, dir, "hall.pbrt");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    kill(batch, SIGKILL);
    int status = 0;
    waitpid(batch, &status, 0);
    ASSERT_GT(render, 0);
    bool gone = false;
    for (int i = 0; i < 500 && !(gone = !Runs(render)); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (!gone) kill(render, SIGKILL);  // clean up after the old code
    EXPECT_TRUE(gone) << "render " << render << " outlived its batch";
}

// SIGTERM of `prism batch` killed it where it stood: report.json said the scene was still
// "running" and its render went on. Now the batch stops its renders as on SIGINT and says why.
TEST(Hostile, TerminatingTheBatchStopsItsRenderAndSaysSoInTheReport) {
    fs::path dir = TempDir("batch_term");
    std::ofstream(dir / "a.pbrt") << kHead << "Shape \"sphere\"\n";
    std::ofstream(dir / "hall.pbrt") << MirrorHall(256, 256, 8, 1000);
    std::ofstream(dir / "c.pbrt") << kHead << "Shape \"sphere\"\n";
    std::ofstream(dir / "list.txt") << "a.pbrt\nhall.pbrt\nc.pbrt\n";
    pid_t batch = Spawn(dir, {"batch", "list.txt", "-o", "out", "--threads", "1", "-q"});
    ASSERT_GT(batch, 0);
    const pid_t render = WaitForRender(batch, dir, "hall.pbrt");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    kill(batch, SIGTERM);
    const int status = WaitOrKill(batch, 60);
    if (render > 0 && Runs(render)) kill(render, SIGKILL);
    const fs::path report = dir / "out/report.json";
    ASSERT_NE(status, -1) << "the batch went on after SIGTERM";
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 130);
    EXPECT_NE(ReadFile(report).find("\"ended_by\": \"SIGTERM"), std::string::npos)
        << ReadFile(report);
    EXPECT_NE(ReportEntry(report, "a.pbrt").find("\"status\": \"ok\""), std::string::npos);
    EXPECT_NE(ReportEntry(report, "hall.pbrt").find("\"status\": \"interrupted\""),
              std::string::npos)
        << ReadFile(report);
    EXPECT_NE(ReportEntry(report, "c.pbrt").find("\"status\": \"pending\""), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "out/hall.png"));
}

// The largest peak resident memory of any child process waited for so far, in MiB (the
// prism processes RunPrism runs, through their shell).
// ASan's shadow memory and quarantine make a child's peak resident size no measure of what
// Prism holds: the peak bounds are checked in the Release build only (the located errors in
// both).
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kPeakIsPrisms = false;
#else
constexpr bool kPeakIsPrisms = true;
#endif

double PeakChildMiB() {
    struct rusage u {};
    getrusage(RUSAGE_CHILDREN, &u);
    return double(u.ru_maxrss) / 1024.0;
}

// --max-memory left what the parser holds uncharged: a million ObjectInstance lines (17 MB)
// or a million nested AttributeBegin (15 MB) grew to many times a 64 MiB budget before
// anything was refused. Each instance and each graphics-state frame is charged as it is
// parsed; the error is at the directive that does not fit.
TEST(Hostile, WhatTheParserHoldsIsChargedToTheBudget) {
    fs::path dir = TempDir("parser_budget");
    {
        std::ofstream f(dir / "instances.pbrt");
        f << kHead << "ObjectBegin \"a\"\nShape \"sphere\"\nObjectEnd\n";
        for (int i = 0; i < 1000000; ++i) f << "ObjectInstance \"a\"\n";
    }
    {
        std::ofstream f(dir / "nested.pbrt");
        f << kHead;
        for (int i = 0; i < 1000000; ++i) f << "AttributeBegin\n";
    }
    for (auto [scene, fragment] :
         {std::pair{"instances.pbrt", "error: ObjectInstance \"a\" needs about"},
          std::pair{"nested.pbrt", "error: AttributeBegin needs about"}}) {
        SCOPED_TRACE(scene);
        RunResult r = RunPrism(std::string("render ") + scene + " -o out.png -q --max-memory 64M",
                               dir, "timeout -k 5 120");
        EXPECT_EQ(r.exitCode, 2) << r.err.substr(0, 2000);
        EXPECT_NE(r.err.find(std::string(scene) + ":"), std::string::npos) << r.err.substr(0, 2000);
        EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err.substr(0, 2000);
        EXPECT_NE(r.err.find("(--max-memory)"), std::string::npos) << r.err.substr(0, 2000);
        EXPECT_FALSE(fs::exists(dir / "out.png"));
        if (kPeakIsPrisms) EXPECT_LT(PeakChildMiB(), 3 * 64.0);
    }
}

// A .spd spectrum file was read whole, whatever --max-memory said; it is now size-checked
// against the budget (reading and converting it takes about ten times its size) first.
TEST(Hostile, SpectrumFilesAreCheckedAgainstTheBudget) {
    fs::path dir = TempDir("spd_budget");
    {
        std::ofstream f(dir / "big.spd");
        const std::string line = "400 1 500 1 600 1 700 1\n";
        for (size_t n = 0; n < (size_t(8) << 20); n += line.size()) f << line;
    }
    std::ofstream(dir / "s.pbrt") << kHead
                                  << "Material \"matte\" \"spectrum Kd\" \"big.spd\"\n"
                                     "Shape \"sphere\"\n";
    RunResult r = RunPrism("render s.pbrt -o out.png -q --max-memory 64M", dir, "timeout -k 5 120");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("s.pbrt:6:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("error: spectrum file \"big.spd\" needs about 80 MiB, more than the "
                         "memory budget of 64 MiB (--max-memory)"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    // Within the budget it is read as before.
    r = RunPrism("render s.pbrt -o out.png -q --max-memory 1G", dir, "timeout -k 5 120");
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

// `prism batch DIR` read every .pbrt in the folder whole to find the files they name, before
// any render and whatever --max-memory said (a 150 MB scene: 150 MB in the batch process).
// The scan now reads a line at a time.
TEST(Hostile, BatchFolderScanDoesNotReadScenesWhole) {
    fs::path dir = TempDir("batch_scan");
    fs::create_directories(dir / "in");
    {
        std::ofstream f(dir / "in/big.pbrt");
        const std::string line = "# " + std::string(98, 'x') + "\n";
        for (int i = 0; i < 1500000; ++i) f << line;
        f << kHead << "Shape \"sphere\"\n";
    }
    RunResult r = RunPrism("batch in -o out -q --max-memory 64M", dir, "timeout -k 5 120");
    EXPECT_EQ(r.exitCode, 2) << r.err;  // the render refuses the 150 MB file itself
    EXPECT_NE(ReadFile(dir / "out/report.json").find("memory budget"), std::string::npos)
        << ReadFile(dir / "out/report.json");
    if (kPeakIsPrisms) EXPECT_LT(PeakChildMiB(), 100.0);
}

// A 2 KB glTF whose 41 nodes each name the next one twice as their children: 2^41 - 1 node
// instances. The reader expanded them one by one, a render that never ends; the expansion is
// now counted per node before the graph is walked and checked against the budget.
TEST(Hostile, GltfNodesSharingChildrenAreCountedBeforeTheyAreExpanded) {
    fs::path dir = TempDir("gltf_dag");
    std::string nodes;
    for (int i = 0; i <= 40; ++i) {
        nodes += i ? ", " : "";
        nodes += i < 40 ? "{\"children\": [" + std::to_string(i + 1) + ", " +
                              std::to_string(i + 1) + "]}"
                        : std::string("{}");
    }
    std::ofstream(dir / "dag.gltf") << "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0,\n"
                                       "\"scenes\": [{\"nodes\": [0]}],\n\"nodes\": ["
                                    << nodes << "]}\n";
    for (const char *budget : {" --max-memory 64M", ""}) {
        SCOPED_TRACE(budget);
        RunResult r =
            RunPrism(std::string("render dag.gltf -o out.png -q") + budget, dir, "timeout -k 5 60");
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find("dag.gltf: error: the node graph (2199023255551 node instances, 0 "
                             "of them meshes: nodes share children) needs about"),
                  std::string::npos)
            << r.err;
        EXPECT_NE(r.err.find("(--max-memory)"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "out.png"));
    }
}

// Temporary files left by writers that were killed are removed when Prism next writes into
// the folder, but only the surely stale ones.
TEST(Hostile, StaleTemporariesOfDeadWritersAreRemoved) {
    fs::path dir = TempDir("stale");
    std::ofstream(dir / "s.pbrt") << kHead << "Shape \"sphere\"\n";
    pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) _exit(0);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);  // `child` names no process any more
    const std::string dead = ".prism-" + std::to_string(child) + "-";
    const std::string alive = ".prism-" + std::to_string(getpid()) + "-";
    const auto old = fs::file_time_type::clock::now() - std::chrono::hours(2);
    auto plant = [&](const std::string &name, bool aged) {
        std::ofstream(dir / name) << "partial";
        if (aged) fs::last_write_time(dir / name, old);
    };
    plant(dead + "a1b2c3.tmp", true);      // stale: removed
    plant(dead + "d4e5f6.log.tmp", true);  // stale render log: removed
    plant(dead + "g7h8i9.tmp", false);     // recent: kept (maybe another machine's)
    plant(alive + "j0k1l2.tmp", true);     // its writer lives: kept
    plant(dead + "m3n4o5.txt", true);      // not a name Prism makes: kept
    plant("keep.txt", true);
    fs::create_symlink("keep.txt", dir / (dead + "p6q7r8.tmp"));  // a link: kept
    RunResult r = RunPrism("render s.pbrt -o out.png -q", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(fs::exists(dir / (dead + "a1b2c3.tmp")));
    EXPECT_FALSE(fs::exists(dir / (dead + "d4e5f6.log.tmp")));
    EXPECT_TRUE(fs::exists(dir / (dead + "g7h8i9.tmp")));
    EXPECT_TRUE(fs::exists(dir / (alive + "j0k1l2.tmp")));
    EXPECT_TRUE(fs::exists(dir / (dead + "m3n4o5.txt")));
    EXPECT_TRUE(fs::is_symlink(dir / (dead + "p6q7r8.tmp")));
    EXPECT_EQ(ReadFile(dir / "keep.txt"), "partial");
}

}  // namespace
}  // namespace prism
