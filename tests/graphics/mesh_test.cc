// Tessellation (graphics/mesh.h): closed solids enclose the volume their
// dimensions give, with every face turned outwards (a positive signed
// volume), in the body frame the shape's pose gives; springs are a unit
// helix placed onto their two points.

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "graphics/mesh.h"
#include "tests/numbers.h"

namespace mechflow::graphics {
namespace {

using mechflow::testing::kPi;

// The signed volume of a closed triangle mesh (divergence theorem): positive
// when every triangle is counter-clockwise seen from outside.
double SignedVolume(const Mesh& m) {
  const auto at = [&](std::uint32_t i) { return Vec3(m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]); };
  double v = 0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3)
    v += at(m.indices[t]).dot(at(m.indices[t + 1]).cross(at(m.indices[t + 2]))) / 6;
  return v;
}

// The area of the regular n-gon inscribed in a circle of radius r over pi r^2.
double Polygon(int n) { return n * std::sin(2 * kPi / n) / (2 * kPi); }

Shape Of(const std::string& kind) {
  Shape s;
  s.kind = kind;
  return s;
}

TEST(MeshTest, SolidsEncloseTheirVolumeFacingOutwards) {
  Shape box = Of("box");
  box.size = {1, 2, 3};
  EXPECT_NEAR(SignedVolume(Tessellate(box)), 6.0, 1e-6);

  Shape cylinder = Of("cylinder");
  cylinder.radius = 0.5, cylinder.length = 2, cylinder.axis = Vec3(1, 1, 0).normalized();
  EXPECT_NEAR(SignedVolume(Tessellate(cylinder)), kPi * 0.25 * 2 * Polygon(32), 1e-6);

  Shape cone = Of("cone");
  cone.radius = 0.5, cone.radius2 = 0.0, cone.length = 3;
  EXPECT_NEAR(SignedVolume(Tessellate(cone)), kPi * 0.25 * 3 / 3 * Polygon(32), 1e-6);

  Shape ellipsoid = Of("ellipsoid");
  ellipsoid.size = {1, 2, 3};
  const double v = SignedVolume(Tessellate(ellipsoid));
  EXPECT_GT(v, 0.97 * 4 * kPi * 6 / 3);  // a polyhedron inside the ellipsoid
  EXPECT_LT(v, 4 * kPi * 6 / 3);

  Shape gear = Of("gear");
  gear.radius = 0.2, gear.length = 0.05, gear.tooth_height = 0.025, gear.teeth = 20;
  const double g = SignedVolume(Tessellate(gear));
  EXPECT_GT(g, kPi * std::pow(0.2 - 0.0125, 2) * 0.05);  // more than the root cylinder
  EXPECT_LT(g, kPi * std::pow(0.2 + 0.0125, 2) * 0.05);  // less than the tip cylinder
  gear.taper = 0.5;                                       // a frustum of the profile: 7/12 of the volume
  EXPECT_NEAR(SignedVolume(Tessellate(gear)), g * (1 + 0.5 + 0.25) / 3, 1e-6 * g);
}

TEST(MeshTest, TheShapesPoseIsApplied) {
  Shape box = Of("box");
  box.size = {2, 2, 2};
  box.position = {1, 2, 3};
  box.rotation = Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix();
  const Mesh m = Tessellate(box);
  Vec3 centre = Vec3::Zero();
  for (int i = 0; i < m.num_vertices(); ++i) centre += Vec3(m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]);
  EXPECT_NEAR((centre / m.num_vertices() - box.position).norm(), 0.0, 1e-6);
  EXPECT_NEAR(m.positions[0], 1 + (std::cos(0.3) * -1 - std::sin(0.3) * -1), 1e-6);  // corner (-1 -1 -1) turned
}

TEST(MeshTest, NormalsOfABoxAreItsFaces) {
  Shape box = Of("box");
  const Mesh m = Tessellate(box);
  const std::vector<float> n = VertexNormals(m);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const Vec3 x(m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]);
    const Vec3 normal(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
    EXPECT_NEAR(normal.norm(), 1.0, 1e-6);
    EXPECT_NEAR(x.dot(normal), 0.5, 1e-6);  // the face's distance from the centre
  }
}

TEST(MeshTest, LinesAndSprings) {
  Shape circle = Of("circle");
  circle.radius = 2;
  const Mesh c = Tessellate(circle);
  EXPECT_EQ(c.primitive, Mesh::Primitive::kLineStrip);
  EXPECT_TRUE(c.indices.empty());
  EXPECT_FLOAT_EQ(c.positions[0], c.positions[c.positions.size() - 3]);  // closed

  Shape spring = Of("spring");
  spring.radius = 0.1, spring.coils = 4, spring.point1 = {0, 0, 1}, spring.point2 = {0, 0, 0};
  const Mesh s = Tessellate(spring);
  EXPECT_EQ(s.num_vertices(), 4 * 24 + 1);
  EXPECT_FLOAT_EQ(s.positions[3 * (s.num_vertices() - 1) + 1], 1.0f);  // unit length along y
  mech::Pose from = mech::Pose::Translation({1, 0, 0}), to = mech::Pose::Translation({1, 0, 3});
  const SpringTransform placed = PlaceSpring(spring, from, to);
  EXPECT_NEAR((placed.translation - Vec3(1, 0, 1)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(placed.length, 2.0, 1e-15);
  EXPECT_NEAR((placed.rotation * Vec3::UnitY() - Vec3::UnitZ()).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace mechflow::graphics
