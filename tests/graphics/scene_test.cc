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
using ::testing::Not;

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
  EXPECT_EQ(scene.shapes[0].name, "sphere 1");
  EXPECT_EQ(scene.shapes[0].identifiers, std::vector<int>{0});  // r
  EXPECT_TRUE(scene.shapes[2].identifiers.empty());
}

TEST(SceneTest, ParametricShapesAreSampledFromTheirExpressions) {
  const Scene scene = Build(
      "<shape type='curve' x='r*cos(u)' y='r*sin(u)' z='0.1*u' u='0 2*pi' samples='8'/>"
      "<shape type='surface' body='B' x='u' y='v' z='u*v*r' u='0 1' v='-1 1' samples='4 2'/>");
  const Parametric& curve = scene.shapes[0].parametric;
  ASSERT_EQ(curve.points.size(), 9u);
  EXPECT_NEAR(curve.points[2].x(), 0.0, 1e-15);  // u = pi/2
  EXPECT_NEAR(curve.points[2].y(), 0.2, 1e-15);
  EXPECT_NEAR(curve.points[8].z(), 0.2 * 3.14159265358979, 1e-12);
  const Parametric& surface = scene.shapes[1].parametric;
  ASSERT_EQ(surface.points.size(), 15u);  // (4 + 1) x (2 + 1), u fastest
  EXPECT_EQ(surface.points[5 * 2 + 4], Vec3(1, 1, 0.2));
  EXPECT_EQ(scene.shapes[1].identifiers, std::vector<int>{0});
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
  EXPECT_THAT(error("<shape type='box' body='B' size='1 0 1'/>"), HasSubstr("every one must be > 0"));
  EXPECT_THAT(error("<shape type='box' color='red'/>"), HasSubstr("expected \"#rrggbb\""));
  EXPECT_THAT(error("<shape type='polyline' points='0 0 0'/>"), HasSubstr("at least two points"));
  EXPECT_THAT(error("<shape type='box' opacity='2'/>"), HasSubstr("must lie in [0, 1]"));
  EXPECT_THAT(error("<shape type='box' radius2='1'/>"), HasSubstr("a box has no 'radius2' (only type=\"cone\" takes it); it takes size and"));
  EXPECT_THAT(error("<shape type='gear' teeth='2.5'/>"), HasSubstr("'teeth': a whole number from 3 to 1000"));
  EXPECT_THAT(error("<shape type='gear' radius='0.1' tooth_height='0.3'/>"), HasSubstr("below twice the radius"));
  EXPECT_THAT(error("<shape type='plane' size='1'/>"), HasSubstr("expected two edges > 0"));
  EXPECT_THAT(error("<shape type='cone' radius2='-1'/>"), HasSubstr("'radius2': must be >= 0"));
  EXPECT_THAT(error("<shape type='curve' x='u' y='0' z='0'/>"), HasSubstr("needs the range 'u'"));
  EXPECT_THAT(error("<shape type='curve' x='u' y='0' u='0 1'/>"), HasSubstr("needs 'z', an expression of u"));
  EXPECT_THAT(error("<shape type='curve' x='w' y='0' z='0' u='0 1'/>"), HasSubstr("unknown name 'w'"));
  EXPECT_THAT(error("<shape type='surface' x='u' y='v' z='0' u='1 0' v='0 1'/>"), HasSubstr("from < to"));
}

TEST(SceneTest, AnAnimationOfNothingIsRefused) {
  const std::string path = ::testing::TempDir() + "no_shapes.xml";
  std::ofstream(path) << Diagram("");
  const auto run = mechflow::testing::RunMechflow("run " + path + " --animate --out " + ::testing::TempDir() + "ns");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("nothing to animate: no <shape> on any body"));
}

TEST(SceneTest, NoAnimateSkipsTheDiagramsAnimationAndSweepsSaySoToo) {
  const std::string path = ::testing::TempDir() + "animated.xml";
  std::ofstream(path) << "<diagram name='a'><identifiers><identifier name='c' value='1'/></identifiers>"
                         "<mechanism name='m'><body name='B' mass='1' inertia='1 1 1'/>"
                         "<joint name='j' type='translational' body1='Base0' body2='B' axis='0 0 1'/>"
                         "<shape type='sphere' body='B'/></mechanism><solver t_end='0.1'/>"
                         "<output animation='a.html' gltf='a.glb'/></diagram>";
  const std::string out = ::testing::TempDir() + "animated_out";
  const auto with = mechflow::testing::RunMechflow("run " + path + " --out " + out);
  EXPECT_THAT(with.out, HasSubstr("a.html ("));
  EXPECT_THAT(with.out, HasSubstr("a.glb ("));
  const auto without = mechflow::testing::RunMechflow("run " + path + " --no-animate --out " + out + "2");
  EXPECT_EQ(without.exit_code, 0) << without.err;
  EXPECT_THAT(without.out, Not(HasSubstr(".html")));
  EXPECT_THAT(without.out, Not(HasSubstr(".glb")));
  EXPECT_EQ(mechflow::testing::RunMechflow("run " + path + " --no-animate --gltf").exit_code, 2);
  const auto sweep = mechflow::testing::RunMechflow("sweep " + path + " --vary c=1,2 --out " + out + "3");
  EXPECT_THAT(sweep.out, HasSubstr("note: a sweep writes no animation"));
}

}  // namespace
}  // namespace mechflow::graphics
