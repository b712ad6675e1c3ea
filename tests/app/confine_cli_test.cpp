// `--confine [DIR]` (issue 17): a corpus of scenes that try to read outside their folder, in
// every format and through every kind of file reference, is refused with exit status 2 and the
// location of the directive that names the file; without --confine the same scenes are read as
// before. The corpus is written at run time, because its absolute paths and symbolic links
// depend on where the test runs.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "support/process.h"
#include "support/shared.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

// Five lines (test::kCliHead); the directive under test goes on line 6.
const std::string kPbrtHead = kCliHead;

const char *const kTriangleObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n";

// A glTF triangle whose position buffer is `bufferUri`, with a base-colour texture `imageUri`
// when given. Returns the text; the buffer's uri is on line 4, the image's on line 5.
std::string Gltf(const std::string &bufferUri, const std::string &imageUri = "") {
    std::string s = "{\"asset\": {\"version\": \"2.0\"},\n";
    s += "\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}],\n";
    s += "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"TEXCOORD_0\": 1}" +
         std::string(imageUri.empty() ? "" : ", \"material\": 0") + "}]}],\n";
    s += "\"buffers\": [{\"byteLength\": 60, \"uri\": \"" + bufferUri + "\"}],\n";
    if (!imageUri.empty())
        s += "\"images\": [{\"uri\": \"" + imageUri +
             "\"}], \"textures\": [{\"source\": 0}],\n"
             "\"materials\": [{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": "
             "0}}}],\n";
    s += "\"bufferViews\": [{\"buffer\": 0, \"byteLength\": 36}, {\"buffer\": 0, "
         "\"byteOffset\": 36, \"byteLength\": 24}],\n";
    s += "\"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": "
         "\"VEC3\", \"min\": [0, 0, 0], \"max\": [1, 1, 0]}, {\"bufferView\": 1, "
         "\"componentType\": 5126, \"count\": 3, \"type\": \"VEC2\"}]}\n";
    return s;
}

std::string TriangleBuffer() {
    const float v[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    return std::string(reinterpret_cast<const char *>(v), sizeof(v));
}

struct EscapeCase {
    std::string scene;     // under scene/
    std::string location;  // "scene/FILE:LINE:" of the directive naming the file
    std::string names;     // a fragment of the refused file's name (as written) in the message
    bool readable;         // whether an unconfined render succeeds
};

// root/outside holds the files the scenes reach for; root/scene the scenes (and symbolic links
// out of it, a FIFO and a link to /dev/zero).
std::vector<EscapeCase> WriteCorpus(const fs::path &root) {
    fs::create_directories(root / "outside");
    fs::create_directories(root / "scene");
    const fs::path out = root / "outside";
    std::ofstream(out / "secret.pbrt") << "Shape \"sphere\" \"float radius\" 0.5\n";
    std::ofstream(out / "m.ply")
        << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
           "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
           "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    std::ofstream(out / "x.spd") << "400 1\n500 1\n600 1\n700 1\n";
    std::ofstream(out / "out.mtl") << "newmtl m\nKd 1 0 0\n";
    std::ofstream(out / "b.bin", std::ios::binary) << TriangleBuffer();
    fs::copy_file(Source + "/tests/golden/whitted_64x48.exr", out / "tex.exr");

    const fs::path sc = root / "scene";
    const std::string abs = fs::canonical(out).string();
    std::vector<EscapeCase> cases;
    auto pbrt = [&](const std::string &name, const std::string &line, const std::string &names,
                    bool readable) {
        std::ofstream(sc / name) << kPbrtHead << line << "\n";
        cases.push_back({name, "scene/" + name + ":6:", names, readable});
    };
    // pbrt: Include, plymesh, imagemap and spectrum files.
    pbrt("include_dotdot.pbrt", "Include \"../outside/secret.pbrt\"", "secret.pbrt", true);
    pbrt("include_absolute.pbrt", "Include \"" + abs + "/secret.pbrt\"", "secret.pbrt", true);
    fs::create_symlink("../outside/secret.pbrt", sc / "link.pbrt");
    pbrt("include_symlink.pbrt", "Include \"link.pbrt\"", "link.pbrt", true);
    pbrt("include_dev_zero.pbrt", "Include \"/dev/zero\"", "/dev/zero", false);
    fs::create_symlink("/dev/zero", sc / "zero.pbrt");
    pbrt("include_symlink_dev_zero.pbrt", "Include \"zero.pbrt\"", "zero.pbrt", false);
    pbrt("include_environ.pbrt", "Include \"/proc/self/environ\"", "environ", false);
    pbrt("import_dotdot.pbrt", "Import \"../outside/secret.pbrt\"", "secret.pbrt", true);
    pbrt("plymesh_dotdot.pbrt", "Shape \"plymesh\" \"string filename\" \"../outside/m.ply\"",
         "m.ply", true);
    pbrt("imagemap_absolute.pbrt",
         "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"" + abs +
             "/tex.exr\" Material \"matte\" \"texture Kd\" \"t\" Shape \"sphere\"",
         "tex.exr", true);
    pbrt("spectrum_dotdot.pbrt",
         "Material \"matte\" \"spectrum Kd\" \"../outside/x.spd\" Shape \"sphere\"", "x.spd", true);
    // A FIFO inside the folder: not a regular file (and opening it must not wait).
    if (::mkfifo((sc / "fifo.pbrt").c_str(), 0600) == 0)
        pbrt("include_fifo.pbrt", "Include \"fifo.pbrt\"", "fifo.pbrt", false);

    // OBJ: mtllib and map_Kd.
    auto obj = [&](const std::string &name, const std::string &mtllib) {
        std::ofstream(sc / name) << "mtllib " << mtllib << "\n" << kTriangleObj;
    };
    obj("mtllib_dotdot.obj", "../outside/out.mtl");
    cases.push_back({"mtllib_dotdot.obj", "scene/mtllib_dotdot.obj:1:", "out.mtl", true});
    fs::create_symlink("../outside/out.mtl", sc / "link.mtl");
    obj("mtllib_symlink.obj", "link.mtl");
    cases.push_back({"mtllib_symlink.obj", "scene/mtllib_symlink.obj:1:", "link.mtl", true});
    obj("mtllib_dev_zero.obj", "../../../../../../../../../../dev/zero");
    cases.push_back({"mtllib_dev_zero.obj", "scene/mtllib_dev_zero.obj:1:", "/dev/zero", false});
    obj("mtllib_environ.obj", "../../../../../../../../../../proc/self/environ");
    cases.push_back({"mtllib_environ.obj", "scene/mtllib_environ.obj:1:", "environ", true});
    std::ofstream(sc / "in.mtl") << "newmtl m\nKd 1 1 1\nmap_Kd ../outside/tex.exr\n";
    obj("map_kd_dotdot.obj", "in.mtl");
    cases.push_back({"map_kd_dotdot.obj", "scene/in.mtl:3:", "tex.exr", true});
    std::ofstream(sc / "abs.mtl") << "newmtl m\nKd 1 1 1\nmap_Kd " << abs << "/tex.exr\n";
    obj("map_kd_absolute.obj", "abs.mtl");
    cases.push_back({"map_kd_absolute.obj", "scene/abs.mtl:3:", "tex.exr", true});

    // glTF: buffer and image URIs (tinygltf reads an absolute URI relative to the file's
    // folder, so only relative paths and links escape).
    std::ofstream(sc / "b.bin", std::ios::binary) << TriangleBuffer();
    std::ofstream(sc / "buffer_dotdot.gltf") << Gltf("../outside/b.bin");
    cases.push_back({"buffer_dotdot.gltf", "scene/buffer_dotdot.gltf:4:", "b.bin", true});
    fs::create_symlink("../outside/b.bin", sc / "link.bin");
    std::ofstream(sc / "buffer_symlink.gltf") << Gltf("link.bin");
    cases.push_back({"buffer_symlink.gltf", "scene/buffer_symlink.gltf:4:", "link.bin", true});
    std::ofstream(sc / "buffer_dev_zero.gltf") << Gltf("../../../../../../../../../../dev/zero");
    cases.push_back({"buffer_dev_zero.gltf", "scene/buffer_dev_zero.gltf:4:", "zero", false});
    std::ofstream(sc / "buffer_environ.gltf")
        << Gltf("../../../../../../../../../../proc/self/environ");
    cases.push_back({"buffer_environ.gltf", "scene/buffer_environ.gltf:4:", "environ", false});
    std::ofstream(sc / "image_dotdot.gltf") << Gltf("b.bin", "../outside/tex.exr");
    cases.push_back({"image_dotdot.gltf", "scene/image_dotdot.gltf:5:", "tex.exr", true});
    return cases;
}

TEST(Confine, EscapingScenesAreRefusedWithTheDirectiveLocation) {
    fs::path root = TempDir("corpus");
    std::vector<EscapeCase> cases = WriteCorpus(root);
    ASSERT_GE(cases.size(), 20u);
    for (const EscapeCase &c : cases) {
        SCOPED_TRACE(c.scene);
        RunResult r = RunPrism(
            "render scene/" + c.scene + " --confine --res 8x8 --spp 1 -o confined.png -q", root);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find(c.location), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(c.names), std::string::npos) << r.err;
        EXPECT_TRUE(r.err.find("outside the confined folder") != std::string::npos ||
                    r.err.find("not a regular file") != std::string::npos)
            << r.err;
        EXPECT_FALSE(fs::exists(root / "confined.png"));

        // The same scene without --confine: read as before.
        RunResult u =
            RunPrism("render scene/" + c.scene + " --res 8x8 --spp 1 -o free.png -q", root);
        if (c.readable) {
            EXPECT_EQ(u.exitCode, 0) << u.err;
            EXPECT_TRUE(fs::exists(root / "free.png"));
        } else {
            EXPECT_NE(u.exitCode, 0);
        }
        EXPECT_EQ(u.err.find("confined"), std::string::npos) << u.err;
        fs::remove(root / "free.png");
    }
}

// Refusals used to say where the path resolves and name the confined folder, both absolute
// (`it resolves to "/srv/.../outside/secret.pbrt", outside the confined folder
// "/srv/.../scene"`): an upload learnt the server's folders from its own errors. They name the
// file as the scene wrote it, and nothing else.
TEST(Confine, RefusalsNameTheFileAsTheSceneWroteIt) {
    fs::path root = TempDir("said");
    std::vector<EscapeCase> cases = WriteCorpus(root);
    const std::string server = fs::canonical(root).string();
    for (const EscapeCase &c : cases) {
        if (c.scene.find("absolute") != std::string::npos) continue;  // the scene wrote it
        SCOPED_TRACE(c.scene);
        RunResult r = RunPrism(
            "render scene/" + c.scene + " --confine --res 8x8 --spp 1 -o confined.png -q", root);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_EQ(r.err.find(server), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("resolves"), std::string::npos) << r.err;
    }
    for (auto [scene, said] :
         {std::pair{"include_dotdot.pbrt",
                    "included file \"../outside/secret.pbrt\": it lies "
                    "outside the confined folder"},
          std::pair{"include_symlink.pbrt", "included file \"link.pbrt\": it lies outside"},
          std::pair{"imagemap_absolute.pbrt", "/outside/tex.exr\": it lies outside"},
          std::pair{"buffer_dotdot.gltf",
                    "cannot read file \"../outside/b.bin\": it lies outside the confined folder"},
          std::pair{"image_dotdot.gltf", "\"../outside/tex.exr\": it lies outside"}}) {
        SCOPED_TRACE(scene);
        RunResult r = RunPrism(std::string("render scene/") + scene +
                                   " --confine --res 8x8 --spp 1 -o confined.png -q",
                               root);
        EXPECT_NE(r.err.find(said), std::string::npos) << r.err;
    }
    // The Film's "filename" outside the folder: the folder is not named either.
    std::string film = kPbrtHead;
    film.replace(film.find("Film \"image\""), 12,
                 "Film \"image\" \"string filename\" \"../stolen.png\"");
    std::ofstream(root / "scene/film.pbrt") << film << "Shape \"sphere\"\n";
    RunResult r = RunPrism("render scene/film.pbrt --confine -q", root);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("Film \"filename\" \"../stolen.png\" is outside the confined folder; "
                         "give the output with -o"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find(server), std::string::npos) << r.err;
}

TEST(Confine, InfoAndValidateAreConfinedToo) {
    fs::path root = TempDir("info");
    WriteCorpus(root);
    RunResult info = RunPrism("info --confine scene/include_dotdot.pbrt", root);
    EXPECT_EQ(info.exitCode, 2) << info.err;
    EXPECT_NE(info.err.find("scene/include_dotdot.pbrt:6:1: error:"), std::string::npos)
        << info.err;
    EXPECT_EQ(RunPrism("info scene/include_dotdot.pbrt", root).exitCode, 0);
    RunResult val = RunPrism("validate scene/plymesh_dotdot.pbrt --confine --out v -q", root);
    EXPECT_EQ(val.exitCode, 2) << val.err;
    EXPECT_NE(val.err.find("scene/plymesh_dotdot.pbrt:6:"), std::string::npos) << val.err;
}

TEST(Confine, AnExplicitFolderAllowsWhatLiesInsideIt) {
    fs::path root = TempDir("dir");
    WriteCorpus(root);
    // DIR = root: ../outside is inside it now; /dev/zero still is not.
    RunResult r = RunPrism("render scene/include_dotdot.pbrt --confine . -o a.png -q", root);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    r = RunPrism("render scene/include_dev_zero.pbrt --confine=. -o b.png -q", root);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("scene/include_dev_zero.pbrt:6:1:"), std::string::npos) << r.err;
    // The scene itself outside DIR.
    r = RunPrism("render scene/include_dotdot.pbrt --confine outside -o c.png -q", root);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("outside the confined folder"), std::string::npos) << r.err;
    r = RunPrism("render scene/include_dotdot.pbrt --confine=missing -o d.png -q", root);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("is not a folder"), std::string::npos) << r.err;
}

// The Film's "filename" names the output when -o is not given (relative to the working
// directory, as in pbrt-v3): under --confine it must lie inside the folder too.
TEST(Confine, FilmFilenameOutsideTheFolderIsRefused) {
    fs::path root = TempDir("film");
    fs::create_directories(root / "scene");
    std::string head = kPbrtHead;
    std::string evil = head;
    evil.replace(evil.find("Film \"image\""), 12,
                 "Film \"image\" \"string filename\" \"stolen.png\"");
    std::ofstream(root / "scene/evil.pbrt") << evil << "Shape \"sphere\"\n";
    RunResult r = RunPrism("render scene/evil.pbrt --confine -q", root);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("scene/evil.pbrt:3:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("outside the confined folder"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(root / "stolen.png"));
    // -o decides: the Film's name is not used.
    r = RunPrism("render scene/evil.pbrt --confine -o mine.png -q", root);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(root / "mine.png"));
    // Without --confine the scene's name is used as before.
    r = RunPrism("render scene/evil.pbrt -q", root);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(root / "stolen.png"));
}

// Every file in `dir` (recursively, links not followed) with its contents, or its link target
// for a symbolic link: what a test compares before and after a run.
std::map<std::string, std::string> Snapshot(const fs::path &dir) {
    std::map<std::string, std::string> files;
    for (const auto &e : fs::recursive_directory_iterator(dir)) {
        std::string name = e.path().lexically_relative(dir).string();
        if (e.is_symlink())
            files[name] = "-> " + fs::read_symlink(e.path()).string();
        else if (e.is_regular_file())
            files[name] = ReadFile(e.path());
    }
    return files;
}

// An upload that ships symbolic links where Prism writes (issue 25): the temporary names the
// old writers used (`.NAME.tmp-PID-N.EXT`, fopen "wb" following the link), the final name, the
// batch's render log and its reports. Nothing outside the folder may change. The run is
// `exec`ed from the shell that planted the links, so PID is the prism process's own.
TEST(Confine, OutputSymlinksAreNeverWrittenThrough) {
    fs::path root = TempDir("write_links");
    fs::create_directories(root / "outside");
    fs::create_directories(root / "scene");
    std::ofstream(root / "outside/victim.txt") << "precious";
    std::ofstream(root / "outside/other.txt") << "also precious";
    const fs::path sc = root / "scene";
    auto film = [](const std::string &name) {
        std::string head = kPbrtHead;
        head.replace(head.find("Film \"image\""), 12,
                     "Film \"image\" \"string filename\" \"" + name + "\"");
        return head + "Shape \"sphere\"\n";
    };
    const auto before = Snapshot(root / "outside");
    // Links named as the old temporaries of this process, for the image and its counters.
    const std::string plant =
        "for n in 0 1 2 3; do ln -s ../outside/victim.txt .out.tmp-$$-$n.png; "
        "ln -s ../outside/victim.txt .out.tmp-$$-$n.exr; done; exec";

    // 1. The image's temporary name: the render succeeds and writes out.png itself.
    std::ofstream(sc / "evil.pbrt") << film("out.png");
    RunResult r = RunPrism("render evil.pbrt --confine -q", sc, plant);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(Snapshot(root / "outside"), before);
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(sc / "out.png")));
    EXPECT_EQ(ReadFile(sc / "out.png").substr(1, 3), "PNG");
    for (const auto &e : fs::directory_iterator(sc))  // no temporary of Prism's left
        EXPECT_EQ(e.path().filename().string().rfind(".prism-", 0), std::string::npos) << e.path();
    // The same through -o (not confined: the caller's name, still never written through).
    r = RunPrism("render evil.pbrt -o out.exr -q", sc, plant);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(Snapshot(root / "outside"), before);

    // 2. The final name is a link: refused at the parameter under --confine, whether it
    // points outside or back inside the folder.
    fs::create_symlink("../outside/victim.txt", sc / "away.png");
    std::ofstream(sc / "keep.png") << "inside";
    fs::create_symlink("keep.png", sc / "back.png");
    for (const char *name : {"away.png", "back.png"}) {
        SCOPED_TRACE(name);
        std::ofstream(sc / "link.pbrt") << film(name);
        r = RunPrism("render link.pbrt --confine -q", sc);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find("link.pbrt:3:"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
        EXPECT_TRUE(fs::is_symlink(sc / name));
    }
    EXPECT_EQ(ReadFile(sc / "keep.png"), "inside");
    EXPECT_EQ(Snapshot(root / "outside"), before);
    // A folder on the way that is a link out of the upload.
    fs::create_symlink("../outside", sc / "sub");
    std::ofstream(sc / "sub.pbrt") << film("sub/out.png");
    r = RunPrism("render sub.pbrt --confine -q", sc);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("sub.pbrt:3:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("outside the confined folder"), std::string::npos) << r.err;
    EXPECT_EQ(Snapshot(root / "outside"), before);

    // 3. A batch whose output folder lies in the upload: the render log's old name
    // (`OUTPUT.log.tmp`, freopen "w") and the reports' temporaries are links out.
    fs::create_directories(root / "up/out");
    std::ofstream(root / "up/s.pbrt") << kPbrtHead << "Shape \"sphere\"\n";
    fs::create_symlink("../../outside/other.txt", root / "up/out/up_s.png.log.tmp");
    const std::string plantReports =
        "for n in 0 1 2 3 4 5 6 7; do ln -s ../../outside/victim.txt "
        "up/out/.report.json.tmp-$$-$n; "
        "ln -s ../../outside/victim.txt up/out/.summary.txt.tmp-$$-$n; done; exec";
    std::ofstream(root / "up/list.txt") << "s.pbrt\n";
    r = RunPrism("batch up/list.txt -o up/out --confine -q", root, plantReports);
    EXPECT_EQ(r.exitCode, 0) << r.err << ReadFile(root / "up/out/report.json");
    EXPECT_EQ(Snapshot(root / "outside"), before);
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(root / "up/out/report.json")));
    EXPECT_NE(ReadFile(root / "up/out/report.json").find("\"status\": \"ok\""), std::string::npos);
}

// The fault library (tests/app/fault_shim) with `faults` ("NAME=value ...").
std::string Faults(const std::string &faults) {
    return "ASAN_OPTIONS=\"${ASAN_OPTIONS}:verify_asan_link_order=0\" LD_PRELOAD='" +
           std::string(PRISM_FAULT_SHIM) + "' " + faults;
}

// A glTF buffer or image URI naming a FIFO (issue 25): tinygltf's own file-exists probe
// opened each candidate with fopen, which waits for a writer forever, in render, info,
// validate and batch alike. Each command must fail at once with the URI's location. `timeout`
// turns a regression into a failure (exit 124) instead of a hung test.
TEST(Confine, GltfUriNamingAFifoFailsFastAtTheUri) {
    fs::path dir = TempDir("gltf_fifo");
    ASSERT_EQ(::mkfifo((dir / "fifo.bin").c_str(), 0600), 0);
    ASSERT_EQ(::mkfifo((dir / "fifo.png").c_str(), 0600), 0);
    std::ofstream(dir / "b.bin", std::ios::binary) << TriangleBuffer();
    std::ofstream(dir / "buffer.gltf") << Gltf("fifo.bin");
    std::ofstream(dir / "image.gltf") << Gltf("b.bin", "fifo.png");
    const std::string timeout = "timeout -k 5 60";
    for (const char *command : {"render", "info", "validate"}) {
        for (auto [scene, at] : {std::pair{"buffer.gltf", "buffer.gltf:4:"},
                                 std::pair{"image.gltf", "image.gltf:5:"}}) {
            SCOPED_TRACE(std::string(command) + " " + scene);
            const std::string quiet = std::string(command) == "info" ? "" : " -q";
            RunResult r = RunPrism(std::string(command) + " " + scene + quiet, dir, timeout);
            EXPECT_EQ(r.exitCode, 2) << r.err;
            EXPECT_NE(r.err.find(std::string(at)), std::string::npos) << r.err;
            EXPECT_NE(r.err.find("not a regular file"), std::string::npos) << r.err;
        }
    }
    std::ofstream(dir / "list.txt") << "buffer.gltf\nimage.gltf\n";
    RunResult r = RunPrism("batch list.txt -o out -q", dir, timeout);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    std::string report = ReadFile(dir / "out/report.json");
    EXPECT_NE(report.find("buffer.gltf:4:"), std::string::npos) << report;
    EXPECT_NE(report.find("image.gltf:5:"), std::string::npos) << report;
}

// Under --confine a glTF URI outside the folder is refused before anything opens it: the
// fault library ends the process (exit 99) if any open or fopen names the file.
TEST(Confine, GltfUriOutsideTheFolderIsNeverOpened) {
    fs::path root = TempDir("gltf_unopened");
    fs::create_directories(root / "outside");
    fs::create_directories(root / "scene");
    std::ofstream(root / "outside/secret.bin", std::ios::binary) << TriangleBuffer();
    fs::copy_file(Source + "/tests/golden/whitted_64x48.exr", root / "outside/secret.exr");
    std::ofstream(root / "scene/b.bin", std::ios::binary) << TriangleBuffer();
    std::ofstream(root / "scene/buffer.gltf") << Gltf("../outside/secret.bin");
    std::ofstream(root / "scene/image.gltf") << Gltf("b.bin", "../outside/secret.exr");
    for (auto [scene, at, file] : {std::tuple{"buffer.gltf", "buffer.gltf:4:", "secret.bin"},
                                   std::tuple{"image.gltf", "image.gltf:5:", "secret.exr"}}) {
        for (const char *command : {"render", "info", "validate"}) {
            SCOPED_TRACE(std::string(command) + " " + scene);
            const std::string quiet = std::string(command) == "info" ? "" : " -q";
            RunResult r = RunPrism(std::string(command) + " scene/" + scene + " --confine" + quiet,
                                   root, Faults("PRISM_FAULT_FORBID_OPEN=" + std::string(file)));
            EXPECT_EQ(r.exitCode, 2) << r.err;
            EXPECT_NE(r.err.find(std::string(at)), std::string::npos) << r.err;
            EXPECT_NE(r.err.find("outside the confined folder"), std::string::npos) << r.err;
        }
    }
}

TEST(Confine, BatchConfinesEachSceneToItsOwnFolder) {
    fs::path root = TempDir("batch");
    WriteCorpus(root);
    fs::create_directories(root / "in/a");
    fs::create_directories(root / "in/b");
    std::ofstream(root / "in/a/good.pbrt") << kPbrtHead << "Include \"part.pbrt\"\n";
    std::ofstream(root / "in/a/part.pbrt") << "Shape \"sphere\"\n";
    // b/evil.pbrt reaches into its sibling folder a/: inside the batch folder, outside its own.
    std::ofstream(root / "in/b/evil.pbrt") << kPbrtHead << "Include \"../a/part.pbrt\"\n";
    RunResult r = RunPrism("batch in -o out --confine -q", root);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    std::string report = ReadFile(root / "out/report.json");
    size_t good = report.find("a/good.pbrt"), evil = report.find("b/evil.pbrt");
    ASSERT_NE(good, std::string::npos) << report;
    ASSERT_NE(evil, std::string::npos) << report;
    std::string goodLine = report.substr(good, report.find('\n', good) - good);
    std::string evilLine = report.substr(evil, report.find('\n', evil) - evil);
    EXPECT_NE(goodLine.find("\"status\": \"ok\""), std::string::npos) << goodLine;
    EXPECT_NE(evilLine.find("\"status\": \"failed\""), std::string::npos) << evilLine;
    EXPECT_NE(evilLine.find("evil.pbrt:6:1: error:"), std::string::npos) << evilLine;
    EXPECT_NE(evilLine.find("outside the confined folder"), std::string::npos) << evilLine;
    // --confine=in: every scene may read anything under in/.
    r = RunPrism("batch in -o out2 --confine=in -q", root);
    EXPECT_EQ(r.exitCode, 0) << r.err << ReadFile(root / "out2/report.json");
    // Without --confine both render.
    r = RunPrism("batch in -o out3 -q", root);
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

}  // namespace
}  // namespace prism
