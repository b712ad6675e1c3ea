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

#include "support/process.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

// Five lines (test::kCliHead); what a case adds starts on line 6.
const std::string kHead = kCliHead;

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
    // The issue's own form: 40 `mix` textures, each mixing its predecessor with itself (and
    // float ones whose amount is the predecessor too: three references a level).
    std::string mix = kHead, mixFloat = kHead;
    mix += "Texture \"t0\" \"spectrum\" \"constant\" \"rgb value\" [0.5 0.5 0.5]\n";
    mixFloat += "Texture \"t0\" \"float\" \"constant\" \"float value\" 0.5\n";
    for (int i = 1; i < 40; ++i) {
        const std::string prev = "\"t" + std::to_string(i - 1) + "\"";
        mix += "Texture \"t" + std::to_string(i) + "\" \"spectrum\" \"mix\" \"texture tex1\" " +
               prev + " \"texture tex2\" " + prev + " \"float amount\" 0.5\n";
        mixFloat += "Texture \"t" + std::to_string(i) + "\" \"float\" \"mix\" \"texture tex1\" " +
                    prev + " \"texture tex2\" " + prev + " \"texture amount\" " + prev + "\n";
    }
    std::ofstream(dir / "mix.pbrt") << mix << "Material \"matte\" \"texture Kd\" \"t39\"\n"
                                    << "Shape \"sphere\"\n";
    ExpectRefused(dir, "mix.pbrt",
                  "mix.pbrt:22:1: error: texture \"t16\": one lookup would evaluate more than "
                  "65536 textures");
    std::ofstream(dir / "mix_float.pbrt")
        << mixFloat << "Material \"matte\" \"texture sigma\" \"t39\"\nShape \"sphere\"\n";
    // 3^11 > 65536 > 3^10: t10 would evaluate (3^11 - 1) / 2 = 88573 textures.
    ExpectRefused(dir, "mix_float.pbrt",
                  "mix_float.pbrt:16:1: error: texture \"t10\": one lookup would evaluate more "
                  "than 65536 textures");
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

// `prism info` printed the scene's names (its file name, shape, material and light types,
// texture filters, the effects' reasons) on standard output as they were; only its
// warning lines were escaped. Everything it prints from the scene is escaped now.
TEST(Hostile, InfoPrintsTheScenesNamesEscaped) {
    fs::path dir = TempDir("info_escapes");
    const std::string scene = "i\x1b[2Jnfo.pbrt";
    std::ofstream(dir / scene)
        << "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\n"
           "Film \"image\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n"
           "LightSource \"po\x1b]0;owned\x07int\"\n"
           "Texture \"c\" \"spectrum\" \"checkerboard\" \"string aamode\" \"n\x1b[1mone\"\n"
           "Material \"pla\x1b[5mstic\"\nShape \"sph\x1b[7mere\"\nShape \"sphere\"\n";
    RunResult r = RunPrism("info '" + scene + "'", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(HasRawControlChars(r.out)) << r.out;
    EXPECT_FALSE(HasRawControlChars(r.err)) << r.err;
    for (const char *escaped : {"i\\x1b[2Jnfo.pbrt", "po\\x1b]0;owned\\x07int", "n\\x1b[1mone",
                                "pla\\x1b[5mstic", "sph\\x1b[7mere"})
        EXPECT_NE(r.out.find(escaped), std::string::npos) << escaped << "\n" << r.out;
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
