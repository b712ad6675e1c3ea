// docs/PBRT4_STATUS.md lists every directive of pbrt-v4's file format and every type each
// takes, with what Prism does with it: simulated, warned (rendered with a substitution or
// without it, and a warning) or rejected (an error). This test holds a small scene for each
// row, builds it, and checks that the table and Prism agree: the table lists exactly the rows
// below (pbrt-v4's format: its parser's directives, and the types its Create functions take),
// and each scene builds without a warning (simulated), with one (warned) or not at all
// (rejected). A change of behaviour that the table does not follow fails here.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>

#include "assembly/build_scene.h"
#include "image/image_io.h"
#include "scene/load_scene.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

using Key = std::pair<std::string, std::string>;  // (directive, type or "—")

// The scene of a probe: the parts a probe replaces, around a lit diffuse sphere.
struct Parts {
    std::string film =
        "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8 "
        "\"string filename\" \"o.exr\"\n";
    std::string camera = "Camera \"perspective\"\n";
    std::string options;  // before WorldBegin
    std::string light = "LightSource \"point\"\n";
    std::string material = "Material \"diffuse\"\n";
    std::string world;  // after the material
    std::string shape = "Shape \"sphere\"\n";
    std::string Text() const {
        return film + camera + options + "WorldBegin\n" + light + material + world + shape;
    }
};

std::map<Key, std::string> Probes() {
    std::map<Key, std::string> p;
    auto add = [&](const std::string &d, const std::string &t, const Parts &parts) {
        p[{d, t}] = parts.Text();
    };
    const std::string none = "—";
    Parts b;
    auto with = [&](auto f) {
        Parts x = b;
        f(x);
        return x;
    };
    // Directives without a type.
    add("WorldBegin", none, b);
    add("AttributeBegin", none, with([](Parts &x) { x.world = "AttributeBegin\nAttributeEnd\n"; }));
    add("AttributeEnd", none, with([](Parts &x) { x.world = "AttributeBegin\nAttributeEnd\n"; }));
    add("Attribute", none,
        with([](Parts &x) { x.world = "Attribute \"shape\" \"float radius\" 0.5\n"; }));
    for (const char *d : {"Identity", "ReverseOrientation"})
        add(d, none, with([&](Parts &x) { x.world = std::string(d) + "\n"; }));
    add("Translate", none, with([](Parts &x) { x.world = "Translate 1 0 0\n"; }));
    add("Scale", none, with([](Parts &x) { x.world = "Scale 1 2 1\n"; }));
    add("Rotate", none, with([](Parts &x) { x.world = "Rotate 30 0 1 0\n"; }));
    add("LookAt", none,
        with([](Parts &x) { x.camera = "LookAt 0 0 -5 0 0 0 0 1 0\n" + x.camera; }));
    add("CoordinateSystem", none, with([](Parts &x) { x.world = "CoordinateSystem \"c\"\n"; }));
    add("CoordSysTransform", none,
        with([](Parts &x) { x.world = "CoordinateSystem \"c\"\nCoordSysTransform \"c\"\n"; }));
    add("Transform", none,
        with([](Parts &x) { x.world = "Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]\n"; }));
    add("ConcatTransform", none,
        with([](Parts &x) { x.world = "ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]\n"; }));
    add("TransformTimes", none, with([](Parts &x) { x.options = "TransformTimes 0 1\n"; }));
    add("ActiveTransform", none, with([](Parts &x) {
            x.world = "ActiveTransform EndTime\nTranslate 0.1 0 0\nActiveTransform All\n";
        }));
    for (const char *d : {"ObjectBegin", "ObjectEnd", "ObjectInstance"})
        add(d, none, with([](Parts &x) {
                x.world = "ObjectBegin \"o\"\nShape \"sphere\"\nObjectEnd\nObjectInstance \"o\"\n";
            }));
    add("Include", none, with([](Parts &x) { x.world = "Include \"part.pbrt\"\n"; }));
    add("Import", none, with([](Parts &x) { x.world = "Import \"part.pbrt\"\n"; }));
    add("MakeNamedMaterial", none, with([](Parts &x) {
            x.material =
                "MakeNamedMaterial \"n\" \"string type\" \"diffuse\"\nNamedMaterial \"n\"\n";
        }));
    add("NamedMaterial", none, with([](Parts &x) {
            x.material =
                "MakeNamedMaterial \"n\" \"string type\" \"diffuse\"\nNamedMaterial \"n\"\n";
        }));
    add("MediumInterface", none, with([](Parts &x) {
            x.world =
                "MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\n"
                "MediumInterface \"m\" \"\"\nMaterial \"interface\"\n";
        }));
    // Typed directives.
    for (const char *t : {"perspective", "orthographic", "spherical"})
        add("Camera", t, with([&](Parts &x) { x.camera = "Camera \"" + std::string(t) + "\"\n"; }));
    add("Camera", "realistic", with([](Parts &x) {
            x.camera =
                "Camera \"realistic\" \"string lensfile\" \"lens.dat\" "
                "\"float focusdistance\" 5 \"float aperturediameter\" 1\n";
        }));
    for (const char *t :
         {"zsobol", "halton", "independent", "paddedsobol", "pmj02bn", "sobol", "stratified"})
        add("Sampler", t,
            with([&](Parts &x) { x.options = "Sampler \"" + std::string(t) + "\"\n"; }));
    for (const char *t : {"rgb", "gbuffer", "spectral"})
        add("Film", t, with([&](Parts &x) {
                x.film = "Film \"" + std::string(t) +
                         "\" \"integer xresolution\" 8 \"integer yresolution\" 8 "
                         "\"string filename\" \"o.exr\"\n";
            }));
    for (const char *t : {"box", "gaussian", "mitchell", "sinc", "triangle"})
        add("PixelFilter", t,
            with([&](Parts &x) { x.options = "PixelFilter \"" + std::string(t) + "\"\n"; }));
    for (const char *t : {"volpath", "path", "bdpt", "mlt", "sppm", "lightpath", "ambientocclusion",
                          "randomwalk", "simplepath"})
        add("Integrator", t,
            with([&](Parts &x) { x.options = "Integrator \"" + std::string(t) + "\"\n"; }));
    add("Integrator", "simplevolpath", with([](Parts &x) {
            x.options = "Integrator \"simplevolpath\"\n";
            x.light = "LightSource \"infinite\"\n";
            x.material = "Material \"interface\"\n";
        }));
    for (const char *t : {"bvh", "kdtree"})
        add("Accelerator", t,
            with([&](Parts &x) { x.options = "Accelerator \"" + std::string(t) + "\"\n"; }));
    const std::pair<const char *, const char *> media[] = {
        {"homogeneous", ""},
        {"uniformgrid", "\"integer nx\" 1 \"integer ny\" 1 \"integer nz\" 1 \"float density\" [1]"},
        {"rgbgrid",
         "\"integer nx\" 1 \"integer ny\" 1 \"integer nz\" 1 \"rgb sigma_a\" [1 1 1] "
         "\"rgb sigma_s\" [1 1 1]"},
        {"cloud", ""},
        {"nanovdb", "\"string filename\" \"cloud.nvdb\""}};
    for (auto [t, params] : media)
        add("MakeNamedMedium", t, with([&](Parts &x) {
                x.world = "MakeNamedMedium \"m\" \"string type\" \"" + std::string(t) + "\" " +
                          params + "\nMediumInterface \"m\" \"\"\nMaterial \"interface\"\n";
            }));
    const std::pair<const char *, const char *> shapes[] = {
        {"sphere", ""},
        {"disk", ""},
        {"cylinder", ""},
        {"trianglemesh", "\"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]"},
        {"bilinearmesh", "\"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]"},
        {"curve", "\"point3 P\" [0 0 0 1 0 0 1 1 0 0 1 0]"},
        {"loopsubdiv", "\"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]"},
        {"plymesh", "\"string filename\" \"quad.ply\""}};
    for (auto [t, params] : shapes)
        add("Shape", t,
            with([&](Parts &x) { x.shape = "Shape \"" + std::string(t) + "\" " + params + "\n"; }));
    const std::pair<const char *, const char *> materials[] = {
        {"diffuse", ""},
        {"coateddiffuse", ""},
        {"coatedconductor", ""},
        {"conductor", ""},
        {"dielectric", ""},
        {"thindielectric", ""},
        {"diffusetransmission", ""},
        {"measured", "\"string filename\" \"m.bsdf\""},
        {"hair", ""},
        {"subsurface", ""},
        {"interface", ""},
        {"mix", "\"string materials\" [\"a\" \"b\"]"}};
    for (auto [t, params] : materials)
        add("Material", t, with([&](Parts &x) {
                x.material =
                    "MakeNamedMaterial \"a\" \"string type\" \"diffuse\"\n"
                    "MakeNamedMaterial \"b\" \"string type\" \"conductor\"\n"
                    "Material \"" +
                    std::string(t) + "\" " + params + "\n";
            }));
    const std::pair<const char *, const char *> textures[] = {
        {"bilerp", ""},
        {"checkerboard", ""},
        {"constant", ""},
        {"directionmix", ""},
        {"dots", ""},
        {"fbm", ""},
        {"imagemap", "\"string filename\" \"t.png\""},
        {"marble", ""},
        {"mix", ""},
        {"ptex", "\"string filename\" \"t.ptx\""},
        {"scale", ""},
        {"windy", ""},
        {"wrinkled", ""}};
    for (auto [t, params] : textures)
        add("Texture", t, with([&](Parts &x) {
                x.material = "Texture \"t\" \"spectrum\" \"" + std::string(t) + "\" " + params +
                             "\nMaterial \"diffuse\" \"texture reflectance\" \"t\"\n";
            }));
    const std::pair<const char *, const char *> lights[] = {
        {"point", ""},
        {"spot", ""},
        {"goniometric", "\"string filename\" \"t.png\""},
        {"projection", "\"string filename\" \"t.png\""},
        {"distant", ""},
        {"infinite", "\"string filename\" \"env.exr\""}};
    for (auto [t, params] : lights)
        add("LightSource", t, with([&](Parts &x) {
                x.light = "LightSource \"" + std::string(t) + "\" " + params + "\n";
            }));
    add("AreaLightSource", "diffuse", with([](Parts &x) {
            x.world = "AttributeBegin\nAreaLightSource \"diffuse\"\nShape \"disk\"\nAttributeEnd\n";
        }));
    for (const char *t : {"srgb", "rec2020", "aces2065-1", "dci-p3"})
        add("ColorSpace", t,
            with([&](Parts &x) { x.options = "ColorSpace \"" + std::string(t) + "\"\n"; }));
    const std::pair<const char *, const char *> options[] = {
        {"disablepixeljitter", "\"bool disablepixeljitter\" true"},
        {"disabletexturefiltering", "\"bool disabletexturefiltering\" true"},
        {"disablewavelengthjitter", "\"bool disablewavelengthjitter\" true"},
        {"displacementedgescale", "\"float displacementedgescale\" 2"},
        {"forcediffuse", "\"bool forcediffuse\" true"},
        {"msereferenceimage", "\"string msereferenceimage\" \"env.exr\""},
        {"msereferenceout", "\"string msereferenceout\" \"mse.txt\""},
        {"pixelstats", "\"bool pixelstats\" true"},
        {"rendercoordsys", "\"string rendercoordsys\" \"world\""},
        {"seed", "\"integer seed\" 3"},
        {"wavefront", "\"bool wavefront\" true"}};
    for (auto [t, params] : options)
        add("Option", t,
            with([&](Parts &x) { x.options = "Option " + std::string(params) + "\n"; }));
    return p;
}

// The files the probes read, beside them.
void WriteInputs(const fs::path &dir) {
    std::ofstream(dir / "lens.dat") << "# radius thickness eta aperture\n"
                                       "20 4 1.5 16\n-20 2 1 16\n0 28 0 8\n";
    std::ofstream(dir / "part.pbrt") << "Shape \"sphere\" \"float radius\" 0.5\n";
    std::ofstream(dir / "quad.ply")
        << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
           "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
           "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    Image t(4, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) t.SetRGB(x, y, RGB(0.5f));
    WriteImage((dir / "t.png").string(), t);
    WriteImage((dir / "env.exr").string(), t);
}

// What Prism does with a probe's scene: "rejected" (an error), "warned" or "simulated", and
// the first message, for the failure report.
std::pair<std::string, std::string> Observe(const fs::path &dir, const std::string &text) {
    const fs::path file = dir / "probe.pbrt";
    std::ofstream(file) << text;
    Diagnostics diag(false);
    try {
        SceneDescription desc = LoadScene(file.string(), diag);
        BuildSettings settings;
        settings.resolution = {8, 8};
        BuildRenderScene(desc, settings, diag);
    } catch (const SceneError &e) {
        return {"rejected", e.what()};
    }
    if (!diag.Warnings().empty()) return {"warned", diag.Warnings()[0].ToString()};
    return {"simulated", ""};
}

// The rows of the table: "| directive | type | status | ... |" after its header.
std::map<Key, std::string> TableRows() {
    std::ifstream in(test::Source + "/docs/PBRT4_STATUS.md");
    EXPECT_TRUE(in) << "docs/PBRT4_STATUS.md";
    std::map<Key, std::string> rows;
    std::string line;
    auto cell = [](std::string s) {
        size_t a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
        s = a == std::string::npos ? "" : s.substr(a, b - a + 1);
        if (s.size() >= 2 && s.front() == '`' && s.back() == '`') s = s.substr(1, s.size() - 2);
        return s;
    };
    while (std::getline(in, line)) {
        if (line.rfind("| ", 0) != 0) continue;
        std::vector<std::string> cells;
        std::stringstream ss(line.substr(1));
        std::string c;
        while (std::getline(ss, c, '|')) cells.push_back(cell(c));
        if (cells.size() < 3 || cells[0] == "directive" || cells[0].rfind("---", 0) == 0) continue;
        EXPECT_TRUE(rows.emplace(Key{cells[0], cells[1]}, cells[2]).second)
            << "twice: " << cells[0] << " " << cells[1];
    }
    return rows;
}

TEST(Pbrt4Status, TheTableListsEveryDirectiveAndTypeAsPrismTreatsIt) {
    const fs::path dir = test::ScratchDir("pbrt4_status");
    WriteInputs(dir);
    const std::map<Key, std::string> probes = Probes();
    const std::map<Key, std::string> rows = TableRows();
    for (const auto &[key, text] : probes) {
        SCOPED_TRACE(key.first + " " + key.second);
        auto row = rows.find(key);
        if (row == rows.end()) {
            ADD_FAILURE() << "docs/PBRT4_STATUS.md has no row for " << key.first << " "
                          << key.second;
            continue;
        }
        const auto [status, message] = Observe(dir, text);
        EXPECT_EQ(status, row->second) << message << "\nscene:\n" << text;
    }
    for (const auto &[key, status] : rows)
        EXPECT_TRUE(probes.count(key)) << "docs/PBRT4_STATUS.md lists " << key.first << " "
                                       << key.second << ", which is not pbrt-v4's";
}

}  // namespace
}  // namespace prism
