// docs/PBRT4_STATUS.md lists every directive of pbrt-v4's file format and every type each
// takes, with what Prism does with it: simulated, warned (rendered with a substitution or
// without it, and a warning) or rejected (an error). This test holds a small scene for each
// row, builds it, and checks that the table and Prism agree: the table lists exactly the rows
// below (pbrt-v4's format: its parser's directives, and the types its Create functions take),
// and each scene builds without a warning (simulated), with one (warned) or not at all
// (rejected). A change of behaviour that the table does not follow fails here.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "support/status_table.h"

namespace prism {
namespace {

using Key = test::StatusKey;

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
    for (const test::SharedProbe &sp : test::SharedDirectiveProbes())
        add(sp.directive, none, with([&](Parts &x) { test::ApplySharedProbe(sp, x); }));
    add("Attribute", none,
        with([](Parts &x) { x.world = "Attribute \"shape\" \"float radius\" 0.5\n"; }));
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

TEST(Pbrt4Status, TheTableListsEveryDirectiveAndTypeAsPrismTreatsIt) {
    test::CheckStatusTable("docs/PBRT4_STATUS.md", "pbrt4_status", Probes());
}

}  // namespace
}  // namespace prism
