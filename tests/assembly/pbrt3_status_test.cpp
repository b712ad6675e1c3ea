// docs/PBRT3_STATUS.md lists every directive of pbrt-v3's file format, every type each takes
// and the parameter families every type of a directive shares, with what Prism does with it:
// simulated, warned (rendered with a substitution or without it, and a warning) or rejected
// (an error). As pbrt4_status_test.cpp does for pbrt-v4, this test holds a small pbrt-v3 scene
// for each row, builds it, and checks that the table and Prism agree: the table lists exactly
// these rows (pbrt-v3's format: its parser's directives, and the types its Make functions
// take), and each scene builds without a warning (simulated), with one (warned) or not at all
// (rejected).
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "support/status_table.h"

namespace prism {
namespace {

using Key = test::StatusKey;

// The scene of a probe: the parts a probe replaces, around a lit matte sphere.
struct Parts {
    std::string film =
        "Film \"image\" \"integer xresolution\" 8 \"integer yresolution\" 8 "
        "\"string filename\" \"o.exr\"\n";
    std::string camera = "Camera \"perspective\"\n";
    std::string options;  // before WorldBegin
    std::string light = "LightSource \"point\"\n";
    std::string material = "Material \"matte\"\n";
    std::string world;  // after the material
    std::string shape = "Shape \"sphere\"\n";
    std::string end = "WorldEnd\n";
    std::string Text() const {
        return film + camera + options + "WorldBegin\n" + light + material + world + shape + end;
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
    add("WorldEnd", none, b);
    for (const test::SharedProbe &sp : test::SharedDirectiveProbes())
        add(sp.directive, none, with([&](Parts &x) { test::ApplySharedProbe(sp, x); }));
    for (const char *d : {"TransformBegin", "TransformEnd"})
        add(d, none, with([](Parts &x) { x.world = "TransformBegin\nTransformEnd\n"; }));
    for (const char *d : {"MakeNamedMaterial", "NamedMaterial"})
        add(d, none, with([](Parts &x) {
                x.material =
                    "MakeNamedMaterial \"n\" \"string type\" \"matte\"\nNamedMaterial \"n\"\n";
            }));
    add("MediumInterface", none, with([](Parts &x) {
            x.options = "Integrator \"volpath\"\n";
            x.world =
                "MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\n"
                "MediumInterface \"m\" \"\"\nMaterial \"\"\n";
        }));
    // Typed directives.
    for (const char *t : {"perspective", "orthographic", "environment"})
        add("Camera", t, with([&](Parts &x) { x.camera = "Camera \"" + std::string(t) + "\"\n"; }));
    add("Camera", "realistic", with([](Parts &x) {
            x.camera =
                "Camera \"realistic\" \"string lensfile\" \"lens.dat\" "
                "\"float focusdistance\" 5 \"float aperturediameter\" 1\n";
        }));
    for (const char *t :
         {"halton", "sobol", "random", "stratified", "lowdiscrepancy", "02sequence", "maxmindist"})
        add("Sampler", t,
            with([&](Parts &x) { x.options = "Sampler \"" + std::string(t) + "\"\n"; }));
    add("Film", "image", b);
    for (const char *t : {"box", "gaussian", "mitchell", "sinc", "triangle"})
        add("PixelFilter", t,
            with([&](Parts &x) { x.options = "PixelFilter \"" + std::string(t) + "\"\n"; }));
    for (const char *t : {"whitted", "directlighting", "path", "volpath", "bdpt", "mlt", "sppm",
                          "ambientocclusion"})
        add("Integrator", t,
            with([&](Parts &x) { x.options = "Integrator \"" + std::string(t) + "\"\n"; }));
    for (const char *t : {"bvh", "kdtree"})
        add("Accelerator", t,
            with([&](Parts &x) { x.options = "Accelerator \"" + std::string(t) + "\"\n"; }));
    const std::pair<const char *, const char *> media[] = {
        {"homogeneous", ""},
        {"heterogeneous",
         "\"integer nx\" 1 \"integer ny\" 1 \"integer nz\" 1 \"float density\" [1] "
         "\"rgb sigma_a\" [1 1 1] \"rgb sigma_s\" [1 1 1]"}};
    for (auto [t, params] : media)
        add("MakeNamedMedium", t, with([&](Parts &x) {
                x.options = "Integrator \"volpath\"\n";
                x.world = "MakeNamedMedium \"m\" \"string type\" \"" + std::string(t) + "\" " +
                          params + "\nMediumInterface \"m\" \"\"\nMaterial \"\"\n";
            }));
    const std::pair<const char *, const char *> shapes[] = {
        {"sphere", ""},
        {"disk", ""},
        {"cylinder", ""},
        {"cone", ""},
        {"paraboloid", ""},
        {"hyperboloid", "\"point p1\" [1 0 0] \"point p2\" [1 1 1]"},
        {"trianglemesh", "\"point P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]"},
        {"plymesh", "\"string filename\" \"quad.ply\""},
        {"curve", "\"point P\" [0 0 0 1 0 0 1 1 0 0 1 0]"},
        {"heightfield", "\"integer nu\" 2 \"integer nv\" 2 \"float Pz\" [0 1 0 1]"},
        {"loopsubdiv", "\"point P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]"},
        {"nurbs",
         "\"integer nu\" 2 \"integer nv\" 2 \"integer uorder\" 2 \"integer vorder\" 2 "
         "\"float uknots\" [0 0 1 1] \"float vknots\" [0 0 1 1] \"float u0\" 0 \"float u1\" 1 "
         "\"float v0\" 0 \"float v1\" 1 \"point P\" [0 0 0 1 0 0 0 1 0 1 1 0]"}};
    for (auto [t, params] : shapes)
        add("Shape", t,
            with([&](Parts &x) { x.shape = "Shape \"" + std::string(t) + "\" " + params + "\n"; }));
    const std::pair<const char *, const char *> materials[] = {
        {"matte", ""},
        {"plastic", ""},
        {"translucent", ""},
        {"glass", ""},
        {"mirror", ""},
        {"metal", ""},
        {"substrate", ""},
        {"uber", ""},
        {"mix", "\"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"b\""},
        {"hair", ""},
        {"subsurface", ""},
        {"kdsubsurface", ""},
        {"fourier", "\"string bsdffile\" \"m.bsdf\""},
        {"disney", ""},
        {"none", ""}};
    for (auto [t, params] : materials)
        add("Material", t, with([&](Parts &x) {
                x.material =
                    "MakeNamedMaterial \"a\" \"string type\" \"matte\"\n"
                    "MakeNamedMaterial \"b\" \"string type\" \"metal\"\n"
                    "Material \"" +
                    std::string(t) + "\" " + params + "\n";
            }));
    const std::pair<const char *, const char *> textures[] = {
        {"bilerp", ""},  {"checkerboard", ""}, {"constant", ""},
        {"dots", ""},    {"fbm", ""},          {"imagemap", "\"string filename\" \"t.png\""},
        {"marble", ""},  {"mix", ""},          {"ptex", "\"string filename\" \"t.ptx\""},
        {"scale", ""},   {"uv", ""},           {"windy", ""},
        {"wrinkled", ""}};
    for (auto [t, params] : textures)
        add("Texture", t, with([&](Parts &x) {
                x.material = "Texture \"t\" \"spectrum\" \"" + std::string(t) + "\" " + params +
                             "\nMaterial \"matte\" \"texture Kd\" \"t\"\n";
            }));
    const std::pair<const char *, const char *> lights[] = {
        {"point", ""},
        {"spot", ""},
        {"goniometric", "\"string mapname\" \"t.png\""},
        {"projection", "\"string mapname\" \"t.png\""},
        {"distant", ""},
        {"infinite", "\"string mapname\" \"env.exr\""}};
    for (auto [t, params] : lights)
        add("LightSource", t, with([&](Parts &x) {
                x.light = "LightSource \"" + std::string(t) + "\" " + params + "\n";
            }));
    add("AreaLightSource", "diffuse", with([](Parts &x) {
            x.world = "AttributeBegin\nAreaLightSource \"diffuse\"\nShape \"disk\"\nAttributeEnd\n";
        }));
    // Parameter families every type of a directive takes.
    add("Material", "(every type) bumpmap", with([](Parts &x) {
            x.material =
                "Texture \"b\" \"float\" \"wrinkled\"\nMaterial \"plastic\" "
                "\"texture bumpmap\" \"b\"\n";
        }));
    add("Shape", "(every type) alpha, shadowalpha", with([](Parts &x) {
            x.shape =
                "Texture \"a\" \"float\" \"checkerboard\"\nShape \"sphere\" "
                "\"texture alpha\" \"a\" \"float shadowalpha\" 0.5\n";
        }));
    add("LightSource", "(every type) scale",
        with([](Parts &x) { x.light = "LightSource \"point\" \"rgb scale\" [2 2 2]\n"; }));
    add("AreaLightSource", "(diffuse) twosided, nsamples", with([](Parts &x) {
            x.world =
                "AttributeBegin\nAreaLightSource \"diffuse\" \"bool twosided\" true "
                "\"integer nsamples\" 4\nShape \"disk\"\nAttributeEnd\n";
        }));
    return p;
}

TEST(Pbrt3Status, TheTableListsEveryDirectiveAndTypeAsPrismTreatsIt) {
    test::CheckStatusTable("docs/PBRT3_STATUS.md", "pbrt3_status", Probes());
}

}  // namespace
}  // namespace prism
