// The bidirectional integrators in participating media (render/bdpt_vertex.h): an isothermal
// enclosure of a medium that only scatters (its radiance is the walls' everywhere, whatever
// the medium: a closed form every strategy must meet, homogeneous and gridded, bdpt and mlt),
// agreement with volpath in a room with a fog-filled glass and a spot light, and the sky hidden
// by an unbounded fog from every strategy, as from volpath's.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "assembly/build_scene.h"
#include "render/renderer.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/text.h"

namespace prism {
namespace {

using namespace test;

RenderScene BuildText(const std::string &name, const std::string &text) {
    return BuildSceneText("bdpt_media", name, text);
}

// The camera inside a black sphere whose inside emits 1, filled with `medium` (declared as
// "fog"), which absorbs nothing: every path ends on the wall, so the image is 1 wherever the
// paths scatter, given enough bounces.
std::string Enclosure(const std::string &integrator, const std::string &medium) {
    return "Film \"image\" \"integer xresolution\" [12] \"integer yresolution\" [8]\n"
           "Sampler \"random\" \"integer pixelsamples\" [256]\n" +
           integrator + "\n" + medium +
           "\nMediumInterface \"\" \"fog\"\nCamera \"perspective\" \"float fov\" [70]\n"
           "WorldBegin\nAttributeBegin\nMediumInterface \"fog\" \"\"\n"
           "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"bool twosided\" true\n"
           "Material \"matte\" \"rgb Kd\" [0 0 0]\nShape \"sphere\" \"float radius\" [2]\n"
           "AttributeEnd\n";
}

const char *Homogeneous =
    "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0 0 0] "
    "\"rgb sigma_s\" [0.8 0.5 0.3] \"float g\" 0.4";
// Denser than the homogeneous fog in places, empty near some corners of its box.
const char *Grid =
    "MakeNamedMedium \"fog\" \"string type\" \"heterogeneous\" \"rgb sigma_a\" [0 0 0] "
    "\"rgb sigma_s\" [1.5 1.5 1.5] \"float g\" -0.3 \"integer nx\" 2 \"integer ny\" 2 "
    "\"integer nz\" 2 \"float density\" [0.1 1 0.5 2 0 1.5 0.7 0.2] \"point3 p0\" [-2 -2 -2] "
    "\"point3 p1\" [2 2 2]";

TEST(BdptMedia, EnclosureOfAScatteringMediumKeepsTheWallsRadiance) {
    for (const char *medium : {Homogeneous, Grid}) {
        SCOPED_TRACE(medium);
        RenderScene scene = BuildText(
            "enclosure", Enclosure("Integrator \"bdpt\" \"integer maxdepth\" [60]", medium));
        RenderStats stats;
        const Image image = RenderWithSeed(scene, 0, &stats);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(MeanChannel(image, c), 1.0, 0.015) << c;
        EXPECT_GT(stats.rays.reflection, 0u);  // paths scattered in the medium
        // Without enough bounces, the paths that scatter most are missing.
        RenderScene shallow = BuildText(
            "enclosure1", Enclosure("Integrator \"bdpt\" \"integer maxdepth\" [1]", medium));
        EXPECT_LT(MeanValue(RenderWithSeed(shallow, 0)), 0.97);
    }
}

TEST(BdptMedia, MltEnclosureKeepsTheWallsRadiance) {
    RenderScene scene = BuildText(
        "mlt_enclosure",
        Enclosure("Integrator \"mlt\" \"integer maxdepth\" [30] \"integer mutationsperpixel\" "
                  "[64] \"integer bootstrapsamples\" [16384] \"integer chains\" [512]",
                  Homogeneous));
    // Over 30 seeds: 1.0028, standard deviation 0.012.
    EXPECT_NEAR(MeanValue(RenderWithSeed(scene, 0)), 1.0, 0.03);
}

// A matte room with a fog-filled glass sphere and a sphere of fog behind an invisible boundary,
// lit by a spot light shining onto the invisible one and by a small area light, and seen
// through a thin fog filling the room. (The spot light misses the glass: volpath cannot
// render the caustic a point light makes through it, which bdpt does.)
std::string FoggyRoom(const std::string &integrator, int spp) {
    return "LookAt 1.6 1.4 1.8  -0.8 1.2 -1.6  0 1 0\n"
           "MakeNamedMedium \"haze\" \"string type\" \"homogeneous\" \"rgb sigma_a\" "
           "[0.02 0.02 0.02] \"rgb sigma_s\" [0.08 0.1 0.12]\n"
           "MakeNamedMedium \"milk\" \"string type\" \"homogeneous\" \"rgb sigma_a\" "
           "[0.1 0.3 0.5] \"rgb sigma_s\" [3 3 3] \"float g\" 0.5\n"
           "MediumInterface \"\" \"haze\"\nCamera \"perspective\" \"float fov\" [70]\n"
           "Film \"image\" \"integer xresolution\" [32] \"integer yresolution\" [24]\n"
           "Sampler \"random\" \"integer pixelsamples\" [" +
           std::to_string(spp) + "]\n" + integrator +
           "\nWorldBegin\nMediumInterface \"haze\" \"haze\"\n"
           "LightSource \"spot\" \"point from\" [0.6 3.8 -0.3] \"point to\" [0.8 0.5 -0.4] "
           "\"rgb I\" [12 12 12] \"float coneangle\" [12]\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [3 3 3]\n"
           "Translate 1 3.4 -1\nShape \"sphere\" \"float radius\" [0.2]\nAttributeEnd\n"
           "Material \"matte\" \"rgb Kd\" [0.7 0.7 0.7]\n" +
           kClosedRoom +
           "AttributeBegin\nMaterial \"glass\"\nMediumInterface \"milk\" \"haze\"\n"
           "Translate -0.6 0.6 -0.9\nShape \"sphere\" \"float radius\" [0.6]\nAttributeEnd\n"
           "AttributeBegin\nMaterial \"none\"\nMediumInterface \"milk\" \"haze\"\n"
           "Translate 0.8 0.5 -0.4\nShape \"sphere\" \"float radius\" [0.5]\nAttributeEnd\n";
}

TEST(BdptMedia, AgreesWithVolpath) {
    RenderScene bdpt = BuildText("room_bdpt", FoggyRoom("Integrator \"bdpt\"", 64));
    RenderScene volpath = BuildText("room_volpath", FoggyRoom("Integrator \"volpath\"", 64));
    EXPECT_TRUE(bdpt.integrator->Traits().media);
    const Image b = RenderWithSeed(bdpt, 0), v1 = RenderWithSeed(volpath, 0),
                v2 = RenderWithSeed(volpath, 1);
    EXPECT_NEAR(MeanValue(b), MeanValue(v1), 0.02 * MeanValue(v1));
    EXPECT_LT(RelL1(b, v1), 1.2 * RelL1(v2, v1));
    RenderScene mlt = BuildText(
        "room_mlt", FoggyRoom("Integrator \"mlt\" \"integer mutationsperpixel\" [64]", 1));
    EXPECT_NEAR(MeanValue(RenderWithSeed(mlt, 0)), MeanValue(v1), 0.04 * MeanValue(v1));
}

// A sky and a sun over a floor, seen from inside a fog that fills all space: no light from
// infinitely far crosses it, for volpath's paths and for every strategy of bdpt's (light
// subpaths from the sky begin in the fog beyond the scene). A grid medium is empty beyond its
// box: there the sky lights the floor as volpath sees it.
TEST(BdptMedia, AnUnboundedFogHidesTheSky) {
    auto scene = [](const std::string &integrator, const std::string &medium) {
        return "LookAt 0 2 6  0 0.5 0  0 1 0\n" + medium +
               "\nMediumInterface \"\" \"fog\"\nCamera \"perspective\" \"float fov\" [40]\n"
               "Film \"image\" \"integer xresolution\" [16] \"integer yresolution\" [12]\n"
               "Sampler \"random\" \"integer pixelsamples\" [64]\n" +
               integrator +
               "\nWorldBegin\nMediumInterface \"fog\" \"fog\"\n"
               "LightSource \"infinite\" \"rgb L\" [0.4 0.5 0.7]\n"
               "LightSource \"distant\" \"point from\" [1 3 2] \"point to\" [0 0 0] "
               "\"rgb L\" [2 2 2]\nMaterial \"matte\" \"rgb Kd\" [0.6 0.6 0.6]\n"
               "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
               "  \"point P\" [-4 0 -4 4 0 -4 4 0 4 -4 0 4]\n";
    };
    const std::string fog =
        "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.05 0.05 "
        "0.05] \"rgb sigma_s\" [0.1 0.1 0.1]";
    RenderScene bdpt = BuildText("sky_fog", scene("Integrator \"bdpt\"", fog));
    EXPECT_LT(MeanValue(RenderWithSeed(bdpt, 0)), 1e-4);
    const std::string grid =
        "MakeNamedMedium \"fog\" \"string type\" \"heterogeneous\" \"rgb sigma_a\" [0.1 0.1 "
        "0.1] \"rgb sigma_s\" [0.5 0.5 0.5] \"integer nx\" 1 \"integer ny\" 1 \"integer nz\" 1 "
        "\"float density\" [1] \"point3 p0\" [-2 0 -2] \"point3 p1\" [2 2 2]";
    RenderScene bdptGrid = BuildText("sky_grid", scene("Integrator \"bdpt\"", grid));
    RenderScene volpath = BuildText("sky_grid_volpath", scene("Integrator \"volpath\"", grid));
    const double v = MeanValue(RenderWithSeed(volpath, 0));
    EXPECT_GT(v, 0.05);
    EXPECT_NEAR(MeanValue(RenderWithSeed(bdptGrid, 0)), v, 0.02 * v);
}

}  // namespace
}  // namespace prism
