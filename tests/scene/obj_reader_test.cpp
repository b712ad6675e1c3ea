// OBJ reader: grouping by material, index forms, normals, and the MTL → pbrt material mapping.
#include "scene/obj_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

size_t Triangles(const ShapeDesc &s) { return s.params.GetInts("indices").size() / 3; }

const MaterialDesc *FindMaterial(const SceneDescription &d, const std::string &name) {
    for (const MaterialDesc &m : d.materials)
        if (m.name == name) return &m;
    return nullptr;
}

bool Near(const RGB &c, float r, float g, float b) {
    return std::abs(c.r - r) < 1e-5f && std::abs(c.g - g) < 1e-5f && std::abs(c.b - b) < 1e-5f;
}

TEST(ObjReader, GroupsNegativeIndicesAndMissingNormals) {
    WriteScratchFile("objt_groups.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
    std::string path = WriteScratchFile("objt_groups.obj",
                                        "mtllib objt_groups.mtl\r\n"
                                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                        "vn 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                        "g quad\nusemtl red\n"
                                        "f -4 -3 -2 -1\n"  // relative indices, no normals
                                        "g tri\nusemtl blue\n"
                                        "f 1/1/1 2/2/1 3/3/1\n"
                                        "usemtl red\n"
                                        "f 1/1/1 3/3/1 4/4/1\n"
                                        "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nv 0.5 1.5 1\n"
                                        "g penta\nusemtl blue\nf -5 -4 -3 -1 -2\n");
    Diagnostics diag;
    SceneDescription d = ReadObjFile(path, diag);
    EXPECT_EQ(d.format, "obj");
    EXPECT_FALSE(d.camera.specified);
    ASSERT_EQ(d.materials.size(), 2u);
    // quad(red) → 1 mesh, tri → blue + red meshes, penta(blue) → 1 mesh.
    ASSERT_EQ(d.shapes.size(), 4u);
    size_t total = 0;
    for (const ShapeDesc &s : d.shapes) {
        EXPECT_EQ(s.type, "trianglemesh");
        total += Triangles(s);
    }
    EXPECT_EQ(total, 2u + 1u + 1u + 3u);

    const ShapeDesc &quad = d.shapes[0];
    EXPECT_EQ(d.materials[size_t(quad.material)].name, "red");
    EXPECT_EQ(Triangles(quad), 2u);
    EXPECT_TRUE(quad.params.GetNormals("N").empty());  // no normals → flat shading
    std::vector<Vec3f> P = quad.params.GetPoint3s("P");
    ASSERT_EQ(P.size(), 4u);  // negative indices resolved to the first four vertices
    for (const Vec3f &p : {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 1, 0), Vec3f(0, 1, 0)})
        EXPECT_NE(std::find(P.begin(), P.end(), p), P.end());

    // The "tri" group has normals and uvs on every face.
    int withNormals = 0;
    for (const ShapeDesc &s : d.shapes)
        if (!s.params.GetNormals("N").empty()) {
            ++withNormals;
            EXPECT_EQ(s.params.GetPoint2s("uv").size(), s.params.GetPoint3s("P").size());
        }
    EXPECT_EQ(withNormals, 2);

    const ShapeDesc &penta = d.shapes[3];
    EXPECT_EQ(Triangles(penta), 3u);
    for (const Vec3f &p : penta.params.GetPoint3s("P")) EXPECT_EQ(p.z, 1.f);
    EXPECT_EQ(diag.Count(), 0u);
}

TEST(ObjReader, MaterialMapping) {
    WriteScratchFile("objt_mats.mtl",
                     "newmtl dull\nKd 0.5 0.25 0.125\nKs 0 0 0\nillum 2\n"
                     "newmtl shiny\nKd 0.2 0.2 0.2\nKs 0.5 0.5 0.5\nNs 98\nillum 2\n"
                     "newmtl mirror\nKd 0 0 0\nKs 0.9 0.8 0.7\nNs 1000\nNi 3.3\nillum 5\n"
                     "newmtl mirror3\nKs 0.5 0.5 0.5\nillum 3\n"
                     "newmtl glass\nKd 0 0 0\nKs 1 1 1\nTf 0.9 1 0.9\nNi 1.33\nillum 7\n"
                     "newmtl faded\nKd 1 1 1\nd 0.5\nTf 1 1 1\nillum 2\n"
                     "newmtl tinted_tf_only\nKd 0.3 0.3 0.3\nTf 1 1 1\nillum 2\n"
                     "newmtl lamp\nKd 0 0 0\nKe 17 12 4\n"
                     "newmtl wood\nKd 0.8 0.8 0.8\nmap_Kd .\\tex\\wood.jpg\n");
    std::string obj = "mtllib objt_mats.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (const char *m :
         {"dull", "shiny", "mirror", "mirror3", "glass", "faded", "tinted_tf_only", "lamp", "wood"})
        obj += std::string("usemtl ") + m + "\nf 1 2 3\n";
    std::string path = WriteScratchFile("objt_mats.obj", obj);
    Diagnostics diag;
    SceneDescription d = ReadObjFile(path, diag);
    ASSERT_EQ(d.materials.size(), 9u);

    const MaterialDesc *m = FindMaterial(d, "dull");
    ASSERT_TRUE(m);
    EXPECT_EQ(m->type, "matte");
    EXPECT_TRUE(Near(m->params.GetRGB("Kd", RGB(0)), 0.5f, 0.25f, 0.125f));

    m = FindMaterial(d, "shiny");
    EXPECT_EQ(m->type, "plastic");
    EXPECT_TRUE(Near(m->params.GetRGB("Ks", RGB(0)), 0.5f, 0.5f, 0.5f));
    EXPECT_NEAR(m->params.GetFloat("roughness", 0), std::sqrt(2.0 / 100.0), 1e-6);
    EXPECT_FALSE(m->params.GetBool("remaproughness", true));

    m = FindMaterial(d, "mirror");
    EXPECT_EQ(m->type, "mirror");
    EXPECT_TRUE(Near(m->params.GetRGB("Kr", RGB(0)), 0.9f, 0.8f, 0.7f));
    EXPECT_EQ(FindMaterial(d, "mirror3")->type, "mirror");

    m = FindMaterial(d, "glass");
    EXPECT_EQ(m->type, "glass");
    EXPECT_NEAR(m->params.GetFloat("index", 0), 1.33, 1e-6);
    EXPECT_TRUE(Near(m->params.GetRGB("Kt", RGB(0)), 0.9f, 1, 0.9f));

    // A dissolve d < 1 without a refracting illumination model is transparency, not glass
    // (issue 13: exporters write d for see-through surfaces); the shapes carry it as alpha.
    m = FindMaterial(d, "faded");
    EXPECT_EQ(m->type, "matte");
    int fadedIndex = int(m - d.materials.data());
    for (const ShapeDesc &s : d.shapes)
        if (s.material == fadedIndex) {
            EXPECT_NEAR(s.params.GetFloat("alpha", 1), 0.5, 1e-6);
            EXPECT_EQ(s.params.GetString("alphamode", ""), "blend");
        }

    EXPECT_EQ(FindMaterial(d, "tinted_tf_only")->type, "matte");  // "Tf 1 1 1" is no filter

    // Emission → an area light on the shapes that use the material.
    ASSERT_EQ(d.areaLights.size(), 1u);
    EXPECT_EQ(d.areaLights[0].type, "diffuse");
    EXPECT_TRUE(Near(d.areaLights[0].params.GetRGB("L", RGB(0)), 17, 12, 4));
    int lampIndex = int(FindMaterial(d, "lamp") - d.materials.data());
    int emissive = 0;
    for (const ShapeDesc &s : d.shapes) {
        EXPECT_EQ(s.areaLight >= 0, s.material == lampIndex);
        emissive += s.areaLight >= 0;
    }
    EXPECT_EQ(emissive, 1);

    m = FindMaterial(d, "wood");
    EXPECT_EQ(m->type, "matte");
    std::string tex = m->params.GetTexture("Kd");
    ASSERT_FALSE(tex.empty());
    ASSERT_EQ(d.textures.size(), 1u);
    EXPECT_EQ(d.textures[0].name, tex);
    EXPECT_EQ(d.textures[0].type, "imagemap");
    EXPECT_FALSE(d.textures[0].isFloat);
    EXPECT_EQ(d.textures[0].params.GetString("filename", ""), "./tex/wood.jpg");
    EXPECT_EQ(d.baseDir + "/", ::testing::TempDir());
}

TEST(ObjReader, MissingMtlIsAWarning) {
    std::string path = WriteScratchFile("objt_nomtl.obj",
                                        "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                        "usemtl ghost\nf 1 2 3\n");
    Diagnostics diag;
    SceneDescription d = ReadObjFile(path, diag);
    ASSERT_EQ(d.shapes.size(), 1u);
    EXPECT_EQ(d.shapes[0].material, -1);  // the default material
    EXPECT_GE(diag.Count(), 1u);
    bool mentions = false;
    for (const Warning &w : diag.Warnings())
        mentions |= w.message.find("nowhere.mtl") != std::string::npos;
    EXPECT_TRUE(mentions);
}

TEST(ObjReader, Errors) {
    Diagnostics diag;
    try {
        ReadObjFile(::testing::TempDir() + "objt_missing.obj", diag);
        ADD_FAILURE() << "expected SceneError";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find("cannot open file"), std::string::npos) << e.what();
    }
    // A face that refers to a vertex that does not exist.
    std::string path = WriteScratchFile("objt_badidx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    EXPECT_THROW(ReadObjFile(path, diag), SceneError);
    path = WriteScratchFile("objt_badidx2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n");
    EXPECT_THROW(ReadObjFile(path, diag), SceneError);
    // Malformed numbers: tinyobjloader would read them as 0.
    path = WriteScratchFile("objt_badnum.obj", "v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n");
    try {
        ReadObjFile(path, diag);
        ADD_FAILURE() << "expected SceneError";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find("objt_badnum.obj:2:5"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("bad number \"abc\""), std::string::npos) << e.what();
    }
    path = WriteScratchFile("objt_nan.obj", "v 0 0 0\nv 1 0 0\nvn 0 nan 1\nf 1 2 3\n");
    EXPECT_THROW(ReadObjFile(path, diag), SceneError);
}

}  // namespace
}  // namespace prism
