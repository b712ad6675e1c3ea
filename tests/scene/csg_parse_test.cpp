// CSGBegin/CSGEnd (Prism extension, docs/FORMAT.md): nodes, operands in order with their own
// transforms and materials, nesting, and the located errors of malformed CSG.
#include <gtest/gtest.h>

#include "scene/pbrt_parser.h"
#include "support/errors.h"

namespace prism {
namespace {

using namespace test;

TEST(CsgParse, NestedNodesKeepOperandsInOrder) {
    SceneDescription d = ParsePbrtText(R"(WorldBegin
Shape "sphere"
AttributeBegin
  Translate 1 0 0
  Material "glass"
  CSGBegin "difference"
    Shape "sphere" "float radius" [ 2 ]
    Material "mirror"
    CSGBegin "union"
      Translate 0 1 0
      Shape "sphere" "float radius" [ 0.5 ]
      Shape "cylinder"
    CSGEnd
    Shape "torus"
  CSGEnd
AttributeEnd
Shape "disk"
WorldEnd)");
    ASSERT_EQ(d.shapes.size(), 2u);  // the two shapes outside the node
    EXPECT_EQ(d.shapes[1].type, "disk");
    ASSERT_EQ(d.csg.size(), 1u);
    const CsgDesc &n = d.csg[0];
    EXPECT_EQ(n.op, "difference");
    EXPECT_EQ(n.loc.line, 6);
    EXPECT_EQ(n.loc.column, 3);
    ASSERT_EQ(n.operands.size(), 3u);
    EXPECT_TRUE(n.operands[0].shape);
    EXPECT_FALSE(n.operands[1].shape);
    EXPECT_TRUE(n.operands[2].shape);
    ASSERT_EQ(n.shapes.size(), 2u);
    EXPECT_EQ(n.shapes[n.operands[0].index].type, "sphere");
    EXPECT_EQ(n.shapes[n.operands[2].index].type, "torus");
    ASSERT_EQ(n.children.size(), 1u);
    const CsgDesc &u = n.children[0];
    EXPECT_EQ(u.op, "union");
    ASSERT_EQ(u.shapes.size(), 2u);
    // Each operand has the CTM and material of its own Shape directive.
    EXPECT_EQ(n.shapes[0].worldFromObject.Point(Vec3d(0, 0, 0)).x, 1);
    EXPECT_EQ(u.shapes[0].worldFromObject.Point(Vec3d(0, 0, 0)).y, 1);
    EXPECT_EQ(d.materials[size_t(n.shapes[0].material)].type, "glass");
    EXPECT_EQ(d.materials[size_t(u.shapes[0].material)].type, "mirror");
    // A CSG node is not a scope: the Translate inside the union applies to the torus too.
    EXPECT_EQ(n.shapes[1].worldFromObject.Point(Vec3d(0, 0, 0)).y, 1);
    // Directive order counts operands.
    EXPECT_EQ(n.shapes[0].directiveIndex, 1);
    EXPECT_EQ(u.shapes[1].directiveIndex, 3);
    EXPECT_EQ(d.shapes[1].directiveIndex, 5);
}

TEST(CsgParse, ErrorsAreLocated) {
    EXPECT_EQ(PbrtErrorOf("WorldBegin\nCSGBegin \"xor\" Shape \"sphere\" CSGEnd"),
              "s.pbrt:2:1: error: unknown CSG operation \"xor\" (expected \"union\", "
              "\"intersection\" or \"difference\")");
    EXPECT_EQ(PbrtErrorOf("WorldBegin\nShape \"sphere\"\nCSGEnd"),
              "s.pbrt:3:1: error: CSGEnd without matching CSGBegin");
    EXPECT_EQ(PbrtErrorOf("WorldBegin\n  CSGBegin \"union\" Shape \"sphere\"\nWorldEnd"),
              "s.pbrt:2:3: error: CSGBegin without matching CSGEnd");
    EXPECT_EQ(
        PbrtErrorOf("WorldBegin\nCSGBegin \"union\"\nCSGBegin \"intersection\" CSGEnd\nCSGEnd"),
        "s.pbrt:3:1: error: CSGBegin \"intersection\" has no operands (empty CSG node)");
    EXPECT_EQ(PbrtErrorOf("WorldBegin ObjectBegin \"o\" Shape \"sphere\" ObjectEnd\n"
                          "CSGBegin \"union\"\n ObjectInstance \"o\" CSGEnd"),
              "s.pbrt:3:2: error: ObjectInstance cannot be a CSG operand (CSGBegin at "
              "s.pbrt:2:1)");
    EXPECT_EQ(PbrtErrorOf("WorldBegin CSGBegin \"union\"\nObjectBegin \"o\""),
              "s.pbrt:2:1: error: ObjectBegin inside CSGBegin (at s.pbrt:1:12) is not supported");
    EXPECT_EQ(PbrtErrorOf("WorldBegin ObjectBegin \"o\"\nCSGBegin \"union\""),
              "s.pbrt:2:1: error: CSGBegin inside ObjectBegin \"o\" is not supported");
    EXPECT_EQ(PbrtErrorOf("CSGBegin \"union\""),
              "s.pbrt:1:1: error: CSGBegin without matching CSGEnd");
}

}  // namespace
}  // namespace prism
