// Shapes in the diagram (graphics/scene.h): what they read and the bad
// geometry they refuse, naming file:line.

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "graphics/scene.h"
#include "tests/cli/mechflow_command.h"
#include "tests/test_util.h"

namespace mechflow::graphics {
namespace {

using ::testing::HasSubstr;

std::string Diagram(const std::string& shapes) {
  return "<diagram name='d'><identifiers><identifier name='r' value='0.2'/></identifiers>\n"
         "<mechanism name='m'><body name='B' mass='1' inertia='1 1 1'/>\n"
         "<joint name='j' type='translational' body1='Base0' body2='B' axis='0 0 1'/>\n" +
         shapes + "\n</mechanism><solver t_end='0.1'/></diagram>";
}

Scene Build(const std::string& shapes) { return BuildScene(mechflow::testing::LoadXml(Diagram(shapes))); }

TEST(SceneTest, ShapesReadTheirGeometryAndExpressions) {
  const Scene scene = Build(
      "<shape type='sphere' body='B' radius='2*r' position='0 0 1' color='#ff0000' opacity='0.5'/>"
      "<shape type='cylinder' body='B' radius='r' length='1' axis='0 2 0'/>"
      "<shape type='polyline' points='0 0 0; 1 0 0; 1 1 0'/>"
      "<shape type='spring' body='B' point1='0 0 1' point2='0 0 0' radius='r' coils='5'/>");
  ASSERT_EQ(scene.shapes.size(), 4u);
  ASSERT_EQ(scene.bodies.size(), 1u);
  EXPECT_EQ(scene.bodies[0].label, "m.B");
  EXPECT_DOUBLE_EQ(scene.shapes[0].radius, 0.4);
  EXPECT_EQ(scene.shapes[0].body, 0);
  EXPECT_EQ(scene.shapes[1].axis, Vec3(0, 1, 0));  // made unit
  EXPECT_EQ(scene.shapes[2].body, -1);             // Base0 by default
  EXPECT_EQ(scene.shapes[3].body, 0);
  EXPECT_EQ(scene.shapes[3].body2, -1);
  EXPECT_EQ(scene.shapes[3].coils, 5);
  EXPECT_THAT(SceneJson(scene, "d"), HasSubstr("\"kind\":\"sphere\",\"name\":\"sphere 1\",\"body\":0"));
}

TEST(SceneTest, BadGeometryIsRefusedAtItsLine) {
  const auto error = [](const std::string& shape) {
    return mechflow::testing::InputErrorOf([&] { Build(shape); });
  };
  EXPECT_THAT(error("<shape type='sphere' body='B' radius='-r'/>"),
              HasSubstr("test.xml:4: shape 'sphere 1' 'radius': must be > 0, got -0.2"));
  EXPECT_THAT(error("<shape type='cylinder' body='B' axis='0 0 0'/>"), HasSubstr("the axis is zero"));
  EXPECT_THAT(error("<shape type='box' body='C'/>"), HasSubstr("mechanism 'm' has no body 'C'"));
  EXPECT_THAT(error("<shape type='cube' body='B'/>"), HasSubstr("unknown shape type 'cube'"));
  EXPECT_THAT(error("<shape type='box' body='B' size='1 0 1'/>"), HasSubstr("every edge must be > 0"));
  EXPECT_THAT(error("<shape type='box' color='red'/>"), HasSubstr("expected \"#rrggbb\""));
  EXPECT_THAT(error("<shape type='polyline' points='0 0 0'/>"), HasSubstr("at least two points"));
  EXPECT_THAT(error("<shape type='box' opacity='2'/>"), HasSubstr("must lie in [0, 1]"));
  EXPECT_THAT(error("<shape type='box' radius2='1'/>"), HasSubstr("radius2"));
}

TEST(SceneTest, AnAnimationOfNothingIsRefused) {
  const std::string path = ::testing::TempDir() + "no_shapes.xml";
  std::ofstream(path) << Diagram("");
  const auto run = mechflow::testing::RunMechflow("run " + path + " --animate --out " + ::testing::TempDir() + "ns");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("nothing to animate: no <shape> on any body"));
}

}  // namespace
}  // namespace mechflow::graphics
