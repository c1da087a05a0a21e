// Mechanisms in diagrams: every kind of bad input names file:line and says
// what was expected, so a user can fix the file; src= files; inputs.
#include <algorithm>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using testing::InputErrorOf;
using testing::LoadXml;

// A diagram holding `mechanism_body` inside <mechanism name="m"> on line 3.
std::string Diagram(const std::string& mechanism_body, const std::string& identifiers = "") {
  return "<diagram>\n<identifiers>" + identifiers + "</identifiers>\n<mechanism name=\"m\">\n" + mechanism_body +
         "\n</mechanism>\n<solver t_end=\"0.1\"/>\n</diagram>\n";
}
const std::string kBox = "<body name=\"Box\" mass=\"1\" inertia=\"1 1 1\"/>\n";
const std::string kHinge = "<joint name=\"j\" type=\"rotational\" body1=\"Base0\" body2=\"Box\" axis=\"1 0 0\"/>\n";

std::string ErrorOf(const std::string& xml) {
  return InputErrorOf([&] { LoadXml(xml); });
}

TEST(MechanismLoaderTest, BadBodies) {
  EXPECT_THAT(ErrorOf(Diagram("<body name=\"B\" mass=\"-1\" inertia=\"1 1 1\"/>")),
              StartsWith("test.xml:4: body 'B': mass must be a positive number of kg (got -1)"));
  EXPECT_THAT(ErrorOf(Diagram("<body name=\"B\" mass=\"1\" inertia=\"1 1 3\"/>")),
              AllOf(StartsWith("test.xml:4: body 'B'"), HasSubstr("triangle inequality")));
  EXPECT_THAT(ErrorOf(Diagram("<body name=\"B\" mass=\"1\" inertia=\"1 1 1\" products=\"2 0 0\"/>")),
              AllOf(StartsWith("test.xml:4: body 'B'"), HasSubstr("positive semi-definite")));
  EXPECT_THAT(ErrorOf(Diagram("<body name=\"B\" mass=\"1\" inertia=\"1 1\"/>")),
              HasSubstr("expected 3 numbers, found 2"));
}

TEST(MechanismLoaderTest, PointMassesWhereNoRotationAboutThemNeedsInertia) {
  // inertia 0 0 0 is a point mass, accepted where no rotation about it needs an inertia
  const std::string dot = "<body name=\"P\" mass=\"2\" inertia=\"0 0 0\" com=\"0 L 0\"/>\n";
  const std::string z = "<sensor name=\"z\" kind=\"position\" body=\"P\" point=\"0 L 0\"/>";
  auto run = [&](const std::string& joint, double length) {
    return testing::RunXml("<diagram>\n<identifiers><identifier name=\"L\" value=\"" + std::to_string(length) +
                           "\"/></identifiers>\n<mechanism name=\"m\">\n" + dot + joint + z +
                           "</mechanism>\n<solver t_end=\"1\" rtol=\"1e-10\" atol=\"1e-12\"/>"
                           "<output interval=\"0.01\"><log signal=\"m.z\"/></output>\n</diagram>\n");
  };
  // sliding: free fall
  const auto fall = run("<joint name=\"j\" type=\"translational\" body1=\"Base0\" body2=\"P\" axis=\"0 0 1\"/>\n", 0.0);
  ASSERT_TRUE(fall.outcome.ok) << fall.outcome.failure;
  EXPECT_NEAR(fall.Column("m.z[2]").back(), -9.81 / 2, 1e-9);
  // on a hinge 0.5 m from it: a simple pendulum released from horizontal,
  // which passes the bottom with speed sqrt(2 g L) -- at z = -L
  const auto swing = run("<joint name=\"j\" type=\"rotational\" body1=\"Base0\" body2=\"P\" axis=\"1 0 0\"/>\n", 0.5);
  ASSERT_TRUE(swing.outcome.ok) << swing.outcome.failure;
  const auto zs = swing.Column("m.z[2]");
  EXPECT_NEAR(*std::min_element(zs.begin(), zs.end()), -0.5, 1e-4);  // on the 0.01 s grid
  // turned about an axis through it: refused at the joint's line
  EXPECT_THAT(ErrorOf(Diagram("<body name=\"P\" mass=\"2\" inertia=\"0 0 0\"/>\n"
                              "<joint name=\"spin\" type=\"rotational\" body1=\"Base0\" body2=\"P\" axis=\"0 0 1\"/>")),
              AllOf(StartsWith("test.xml:5: joint 'spin': coordinate 'spin' turns body 'P'"),
                    HasSubstr("has rotational inertia about it"), HasSubstr("Give the body inertia")));
  EXPECT_THAT(ErrorOf(Diagram("<body name=\"P\" mass=\"2\" inertia=\"0 0 0\"/>\n"
                              "<joint name=\"free\" type=\"quaternion\" body1=\"Base0\" body2=\"P\"/>")),
              StartsWith("test.xml:5: joint 'free': coordinate 'free.wx' turns body 'P'"));
  // a rod along x (no moment about its own axis) may spin about y, not x
  EXPECT_NO_THROW(LoadXml(Diagram("<body name=\"R\" mass=\"1\" inertia=\"0 1 1\"/>\n"
                                  "<joint name=\"j\" type=\"rotational\" body1=\"Base0\" body2=\"R\" axis=\"0 1 0\"/>")));
  EXPECT_THAT(ErrorOf(Diagram("<body name=\"R\" mass=\"1\" inertia=\"0 1 1\"/>\n"
                              "<joint name=\"j\" type=\"rotational\" body1=\"Base0\" body2=\"R\" axis=\"1 0 0\"/>")),
              HasSubstr("has rotational inertia about it"));
  EXPECT_THAT(ErrorOf(Diagram("<body name=\"B\" mass=\"1\" inertia=\"-1 1 1\"/>")),
              AllOf(StartsWith("test.xml:4: body 'B'"), HasSubstr("positive semi-definite")));
}

TEST(MechanismLoaderTest, BadJoints) {
  EXPECT_THAT(ErrorOf(Diagram(kBox + "<joint name=\"j\" type=\"rotational\" body1=\"Base0\" body2=\"Bx\"/>")),
              AllOf(StartsWith("test.xml:5: joint 'j': unknown body 'Bx'")));
  EXPECT_THAT(ErrorOf(Diagram(kBox)), StartsWith("test.xml:4: body 'Box' is not connected to Base0"));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + "<joint name=\"k\" type=\"rotational\" body1=\"Base0\" body2=\"Box\" "
                                              "axis=\"0 1 0\"/>")),
              AllOf(StartsWith("test.xml:6: joint 'k' over-constrains the mechanism"), HasSubstr("'Box'")));
  EXPECT_THAT(ErrorOf(Diagram(kBox + "<joint name=\"j\" type=\"rotational\" body1=\"Base0\" body2=\"Box\" "
                                     "axis=\"0 0 0\"/>")),
              AllOf(StartsWith("test.xml:5: joint 'j'"), HasSubstr("axis vector must be non-zero")));
  EXPECT_THAT(ErrorOf(Diagram(kBox + "<joint name=\"j\" type=\"hinge\" body1=\"Base0\" body2=\"Box\"/>")),
              StartsWith("test.xml:5: joint 'j': unknown type 'hinge'"));
  EXPECT_THAT(ErrorOf(Diagram(kBox + "<joint name=\"j\" type=\"generalized\" body1=\"Base0\" body2=\"Box\">\n"
                                     "<et type=\"rx\" axis=\"1 0 0\"/></joint>")),
              AllOf(StartsWith("test.xml:6: joint 'j' transformation 1: unknown transformation type 'rx'"),
                    HasSubstr("tc, tt, tv, rc, rt, rv")));
  EXPECT_THAT(ErrorOf(Diagram(kBox + "<joint name=\"j\" type=\"generalized\" body1=\"Base0\" body2=\"Box\">\n"
                                     "<et type=\"rt\" axis=\"1 0 0\" value=\"omga*t\"/></joint>",
                              "<identifier name=\"omega\" value=\"1\"/>")),
              AllOf(StartsWith("test.xml:6: joint 'j' transformation 1: time function 'omga*t'"),
                    HasSubstr("did you mean 'omega'?")));
}

TEST(MechanismLoaderTest, BadElementsAndSensors) {
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + "<sensor name=\"s\" kind=\"element\" element=\"sprng\"/>")),
              StartsWith("test.xml:6: sensor 's' attribute 'element': unknown element 'sprng'"));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + "<force name=\"sprng\" type=\"linear\" body1=\"Base0\" body2=\"Box\" "
                                              "point1=\"0 0 1\" c=\"1\"/>\n"
                                              "<sensor name=\"s\" kind=\"element\" element=\"spring\"/>")),
              AllOf(StartsWith("test.xml:7: sensor 's' attribute 'element': unknown element 'spring'"),
                    HasSubstr("did you mean 'sprng'?")));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + "<sensor name=\"s\" kind=\"coordinate\" dof=\"jj\"/>")),
              StartsWith("test.xml:6: sensor 's': unknown coordinate 'jj' (did you mean 'j'?)"));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + "<sensor name=\"s\" kind=\"speed\" dof=\"j\"/>")),
              StartsWith("test.xml:6: sensor 's' attribute 'kind': unknown sensor kind 'speed'"));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + "<joint_force name=\"f\" dof=\"j\" type=\"points\" points=\"0 1; 0 2\"/>")),
              AllOf(StartsWith("test.xml:6: joint_force 'f' attribute 'points'"), HasSubstr("increase strictly")));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + "<input name=\"Fz\"/>")),
              StartsWith("test.xml:6: input 'Fz' must name an identifier"));
}

TEST(MechanismLoaderTest, StickModels) {
  // exact stick has no spring: a c or d there would do nothing
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge +
                              "<joint_force name=\"f\" dof=\"j\" type=\"frictional\" friction=\"1\" stick=\"exact\" "
                              "c=\"1e6\"/>")),
              AllOf(StartsWith("test.xml:6: joint_force 'f' attribute 'c'"), HasSubstr("would have no effect")));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge +
                              "<force name=\"f\" type=\"frictional\" body1=\"Base0\" point1=\"0 0 1\" body2=\"Box\" "
                              "friction=\"1\" stick=\"glue\"/>")),
              AllOf(StartsWith("test.xml:6: force 'f' attribute 'stick': unknown stick model 'glue'"),
                    HasSubstr("spring"), HasSubstr("exact")));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge +
                              "<force name=\"f\" type=\"elastic_friction\" body1=\"Base0\" point1=\"0 0 1\" "
                              "body2=\"Box\" friction=\"1\" c=\"100\" stick=\"exact\"/>")),
              AllOf(StartsWith("test.xml:6: force 'f' attribute 'stick': an elastic_friction force has no 'stick' "
                               "(only type=\"frictional\" takes it)"),
                    HasSubstr("already sticks exactly")));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + "<joint_force name=\"f\" dof=\"j\" type=\"linear\" c=\"1\" "
                                              "stick=\"exact\"/>")),
              StartsWith("test.xml:6: joint_force 'f' attribute 'stick': a linear joint_force has no 'stick' "
                         "(only type=\"frictional\" takes it)"));
  // and it has no deflection to sense
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge +
                              "<joint_force name=\"f\" dof=\"j\" type=\"frictional\" friction=\"1\" stick=\"exact\"/>"
                              "<sensor name=\"s\" kind=\"element\" element=\"f\" quantity=\"deflection\"/>")),
              AllOf(HasSubstr("deflection"), HasSubstr("force")));
}

// Attributes a type takes but whose part of the law is absent would change
// nothing: refused, saying what to give instead.
TEST(MechanismLoaderTest, AttributesThatCannotTakeEffectAreRefused) {
  const std::string contact = "<contact name=\"k\" type=\"points_plane\" body1=\"Box\" body2=\"Base0\" "
                              "points=\"0 0 0\" stiffness=\"1e5\"";
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + contact + " v_eps=\"1e-3\"/>")),
              AllOf(StartsWith("test.xml:6: contact 'k' attribute 'v_eps': shapes the friction, but mu and mu_static "
                               "are 0"),
                    HasSubstr("give mu, or remove v_eps")));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + contact + " stribeck_velocity=\"1e-2\"/>")),
              HasSubstr("attribute 'stribeck_velocity': shapes the friction"));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + contact + " damping_depth=\"1e-3\"/>")),
              AllOf(StartsWith("test.xml:6: contact 'k' attribute 'damping_depth'"), HasSubstr("damping is 0")));
  // with friction and damping they take effect
  EXPECT_EQ(ErrorOf(Diagram(kBox + kHinge + contact +
                            " mu=\"0.3\" v_eps=\"1e-3\" damping=\"10\" damping_depth=\"1e-3\"/>")),
            "");
  const std::string ef2 = "<force name=\"f\" type=\"elastic_friction2\" body1=\"Base0\" point1=\"0 0 1\" "
                          "body2=\"Box\" c1=\"100\" mu=\"0.2\" normal_force=\"10\"";
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + ef2 + "/>")),
              AllOf(StartsWith("test.xml:6: force 'f' attribute 'normal_force': is the normal force of "
                               "limit=\"constant\" only"),
                    HasSubstr("with limit=\"transmitted\" it would change nothing")));
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + ef2 + " limit=\"spring\"/>")),
              HasSubstr("with limit=\"spring\" it would change nothing"));
  EXPECT_EQ(ErrorOf(Diagram(kBox + kHinge + ef2 + " limit=\"constant\"/>")), "");
  // a scalar sensor has no component to pick, a constant transformation no name
  EXPECT_THAT(ErrorOf(Diagram(kBox + kHinge + "<sensor name=\"s\" kind=\"coordinate\" dof=\"j\" component=\"x\"/>")),
              StartsWith("test.xml:6: sensor 's' attribute 'component': a coordinate sensor has no 'component'"));
}

TEST(MechanismLoaderTest, MechanismFromItsOwnFileAndAnInputDrivenForce) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / ("mech_src_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "box.xml") << "<mechanism name=\"ignored\" gravity=\"0 0 0\">\n" << kBox
                                 << "<joint name=\"j\" type=\"translational\" body1=\"Base0\" body2=\"Box\" "
                                    "axis=\"0 0 1\"/>\n"
                                    "<input name=\"push\"/>\n"
                                    "<applied_force name=\"f\" body=\"Box\" force=\"0 0 push\"/>\n"
                                    "<sensor name=\"a\" kind=\"acceleration\" dof=\"j\"/>\n"
                                    "</mechanism>\n";
  const std::string diagram =
      "<diagram>\n<identifiers><identifier name=\"push\" value=\"0\"/></identifiers>\n"
      "<mechanism name=\"m\" src=\"box.xml\"/>\n"
      "<blocks><block type=\"constant\" name=\"c\" value=\"3\"/></blocks>\n"
      "<connections><connect from=\"c.y\" to=\"m.push\"/></connections>\n"
      "<solver t_end=\"0.1\"/><output><log signal=\"m.a\"/></output>\n</diagram>\n";
  std::ofstream(dir / "d.xml") << diagram;
  auto loaded = diagrams::LoadDiagram((dir / "d.xml").string());
  blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  ASSERT_TRUE(sim.Run().ok);
  EXPECT_NEAR(sim.results().at(sim.results().num_rows() - 1, 1), 3.0, 1e-12);  // F / m
  // A bad line in the mechanism file is reported in that file.
  std::ofstream(dir / "box.xml") << "<mechanism name=\"x\">\n<body name=\"B\" mass=\"0\" inertia=\"1 1 1\"/>\n"
                                    "</mechanism>\n";
  EXPECT_THAT(InputErrorOf([&] { diagrams::LoadDiagram((dir / "d.xml").string()); }),
              StartsWith((dir / "box.xml").string() + ":2: body 'B': mass must be a positive number"));
}

}  // namespace
}  // namespace mechflow

namespace mechflow {
namespace {

TEST(MechanismLoaderTest, SingularMassMatrixFailsTheRunWithItsTime) {
  // A point-like body spinning about an axis through its centre of mass: no
  // inertia about the joint axis. The run fails (exit 1 in the CLI) naming
  // the joint and the time; the rows before stay.
  const auto run = testing::RunXml(
      "<diagram>\n<mechanism name=\"m\">\n"
      "<body name=\"Dot\" mass=\"1\" inertia=\"1e-20 1e-20 1e-20\"/>\n"
      "<joint name=\"spin\" type=\"rotational\" body1=\"Base0\" body2=\"Dot\" axis=\"0 0 1\" v0=\"1\"/>\n"
      "<sensor name=\"a\" kind=\"coordinate\" dof=\"spin\"/>\n"
      "</mechanism>\n<solver t_end=\"1\"/><output><log signal=\"m.a\"/></output>\n</diagram>\n");
  EXPECT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure, HasSubstr("singular mass matrix at t = 0"));
  EXPECT_THAT(run.outcome.failure, HasSubstr("joint 'spin'"));
  EXPECT_GE(run.sim->results().num_rows(), 1);
}

}  // namespace
}  // namespace mechflow
