#include "graphics/mesh.h"

#include <cmath>

#include <Eigen/Geometry>

namespace mechflow::graphics {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSegments = 32;  // around round shapes
constexpr int kRings = 16;     // pole to pole of spheres and ellipsoids

// Builds a mesh in the shape's own frame, then places it in the body frame.
class MeshBuilder {
 public:
  explicit MeshBuilder(Mesh::Primitive primitive) { mesh_.primitive = primitive; }
  std::uint32_t Vertex(const Vec3& x) {
    points_.push_back(x);
    return static_cast<std::uint32_t>(points_.size() - 1);
  }
  void Triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) { mesh_.indices.insert(mesh_.indices.end(), {a, b, c}); }
  // a quad a b c d, counter-clockwise seen from its front
  void Quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    Triangle(a, b, c);
    Triangle(a, c, d);
  }
  // a flat quad of its own four vertices (a sharp edge to its neighbours)
  void FlatQuad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const std::uint32_t i = Vertex(a);
    Vertex(b), Vertex(c), Vertex(d);
    Quad(i, i + 1, i + 2, i + 3);
  }
  // a flat polygon, star-shaped about `centre`, counter-clockwise seen from its front
  void Fan(const Vec3& centre, const std::vector<Vec3>& ring) {
    const std::uint32_t c = Vertex(centre);
    for (const Vec3& p : ring) Vertex(p);
    const auto n = static_cast<std::uint32_t>(ring.size());
    for (std::uint32_t k = 0; k < n; ++k) Triangle(c, c + 1 + k, c + 1 + (k + 1) % n);
  }
  Mesh Finish(const Mat3& R, const Vec3& p, bool double_sided = false) {
    for (const Vec3& x : points_) {
      const Vec3 y = R * x + p;
      mesh_.positions.insert(mesh_.positions.end(), {float(y.x()), float(y.y()), float(y.z())});
    }
    mesh_.double_sided = double_sided;
    return std::move(mesh_);
  }

 private:
  Mesh mesh_;
  std::vector<Vec3> points_;
};

// The rotation taking the shape frame's z onto `axis`.
Mat3 ZOnto(const Vec3& axis) { return Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), axis).toRotationMatrix(); }

Vec3 Circle(double r, double angle, double z) { return {r * std::cos(angle), r * std::sin(angle), z}; }

void Box(const Vec3& size, MeshBuilder* m) {
  const Vec3 h = size / 2;
  for (int axis = 0; axis < 3; ++axis)
    for (const double side : {-1.0, 1.0}) {
      Vec3 n = Vec3::Zero(), u = Vec3::Zero(), v = Vec3::Zero();
      n[axis] = side * h[axis];
      u[(axis + 1) % 3] = h[(axis + 1) % 3];
      v[(axis + 2) % 3] = side * h[(axis + 2) % 3];
      m->FlatQuad(n - u - v, n + u - v, n + u + v, n - u + v);
    }
}

void Ellipsoid(const Vec3& radii, MeshBuilder* m) {
  for (int i = 0; i <= kRings; ++i) {
    const double polar = kPi * i / kRings;
    for (int k = 0; k < kSegments; ++k) {
      const double a = 2 * kPi * k / kSegments;
      m->Vertex(radii.cwiseProduct(Vec3(std::sin(polar) * std::cos(a), std::sin(polar) * std::sin(a), std::cos(polar))));
    }
  }
  for (int i = 0; i < kRings; ++i)
    for (int k = 0; k < kSegments; ++k) {
      const auto at = [&](int ii, int kk) { return static_cast<std::uint32_t>(ii * kSegments + kk % kSegments); };
      m->Quad(at(i, k), at(i + 1, k), at(i + 1, k + 1), at(i, k + 1));
    }
}

// A frustum along z from (z0, r0) to (z1, r1) with its end discs.
void Frustum(double z0, double r0, double z1, double r1, MeshBuilder* m) {
  const std::uint32_t first = m->Vertex(Circle(r0, 0, z0));
  m->Vertex(Circle(r1, 0, z1));
  for (int k = 1; k < kSegments; ++k) m->Vertex(Circle(r0, 2 * kPi * k / kSegments, z0)), m->Vertex(Circle(r1, 2 * kPi * k / kSegments, z1));
  for (int k = 0; k < kSegments; ++k) {
    const std::uint32_t a = first + 2 * k, b = first + 2 * ((k + 1) % kSegments);
    m->Quad(a, b, b + 1, a + 1);
  }
  std::vector<Vec3> bottom, top;
  for (int k = 0; k < kSegments; ++k) {
    bottom.push_back(Circle(r0, -2 * kPi * k / kSegments, z0));  // clockwise seen from +z: faces -z
    top.push_back(Circle(r1, 2 * kPi * k / kSegments, z1));
  }
  if (r0 > 0) m->Fan({0, 0, z0}, bottom);
  if (r1 > 0) m->Fan({0, 0, z1}, top);
}

// A spur gear along z, centred: trapezoidal teeth between the root radius
// r - h/2 and the tip radius r + h/2; the +z face scaled by `taper`.
void Gear(const Shape& s, MeshBuilder* m) {
  const double pitch = 2 * kPi / s.teeth, root = s.radius - s.tooth_height / 2, tip = s.radius + s.tooth_height / 2;
  std::vector<Vec3> profile;  // counter-clockwise about z
  for (int k = 0; k < s.teeth; ++k) {
    const double a = k * pitch;
    profile.push_back(Circle(root, a, 0));
    profile.push_back(Circle(tip, a + 0.2 * pitch, 0));
    profile.push_back(Circle(tip, a + 0.45 * pitch, 0));
    profile.push_back(Circle(root, a + 0.65 * pitch, 0));
  }
  const double z = s.length / 2;
  const auto front = [&](const Vec3& p) { return Vec3(p.x(), p.y(), -z); };
  const auto back = [&](const Vec3& p) { return Vec3(s.taper * p.x(), s.taper * p.y(), z); };
  std::vector<Vec3> bottom, top;
  for (auto p = profile.rbegin(); p != profile.rend(); ++p) bottom.push_back(front(*p));
  for (const Vec3& p : profile) top.push_back(back(p));
  m->Fan({0, 0, -z}, bottom);
  m->Fan({0, 0, z}, top);
  for (std::size_t k = 0; k < profile.size(); ++k) {
    const Vec3& a = profile[k];
    const Vec3& b = profile[(k + 1) % profile.size()];
    m->FlatQuad(front(a), front(b), back(b), back(a));
  }
}

void Grid(const Parametric& p, MeshBuilder* m) {
  for (const Vec3& x : p.points) m->Vertex(x);
  const int row = p.samples_u + 1;
  for (int j = 0; j < p.samples_v; ++j)
    for (int i = 0; i < p.samples_u; ++i) {
      const auto a = static_cast<std::uint32_t>(j * row + i);
      m->Quad(a, a + 1, a + 1 + row, a + row);
    }
}

}  // namespace

Mesh Tessellate(const Shape& s) {
  using P = Mesh::Primitive;
  const std::string& k = s.kind;
  const bool line = k == "polyline" || k == "circle" || k == "curve" || k == "spring";
  MeshBuilder m(line ? P::kLineStrip : P::kTriangles);
  Mat3 R = s.rotation;
  if (k == "box") {
    Box(s.size, &m);
  } else if (k == "sphere") {
    Ellipsoid(Vec3::Constant(s.radius), &m);
  } else if (k == "ellipsoid") {
    Ellipsoid(s.size, &m);
  } else if (k == "cylinder") {
    Frustum(-s.length / 2, s.radius, s.length / 2, s.radius, &m);
    R = R * ZOnto(s.axis);
  } else if (k == "cone") {
    Frustum(0, s.radius, s.length, s.radius2, &m);
    R = R * ZOnto(s.axis);
  } else if (k == "gear") {
    Gear(s, &m);
    R = R * ZOnto(s.axis);
  } else if (k == "plane") {
    m.FlatQuad({-s.size.x() / 2, -s.size.y() / 2, 0}, {s.size.x() / 2, -s.size.y() / 2, 0},
               {s.size.x() / 2, s.size.y() / 2, 0}, {-s.size.x() / 2, s.size.y() / 2, 0});
    return m.Finish(R, s.position, true);
  } else if (k == "surface") {
    Grid(s.parametric, &m);
    return m.Finish(R, s.position, true);
  } else if (k == "circle") {
    for (int i = 0; i <= 2 * kSegments; ++i) m.Vertex(Circle(s.radius, kPi * i / kSegments, 0));
  } else if (k == "polyline") {
    for (const Vec3& p : s.points) m.Vertex(p);
  } else if (k == "curve") {
    for (const Vec3& p : s.parametric.points) m.Vertex(p);
  } else if (k == "spring") {
    const int n = 24 * s.coils;
    for (int i = 0; i <= n; ++i) {
      const double a = 2 * kPi * s.coils * i / n;
      m.Vertex({s.radius * std::cos(a), double(i) / n, s.radius * std::sin(a)});
    }
    return m.Finish(Mat3::Identity(), Vec3::Zero());  // placed at every frame
  }
  return m.Finish(R, s.position);
}

std::vector<float> VertexNormals(const Mesh& mesh) {
  std::vector<Vec3> sum(mesh.num_vertices(), Vec3::Zero());
  const auto at = [&](std::uint32_t i) {
    return Vec3(mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]);
  };
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    const Vec3 n = (at(b) - at(a)).cross(at(c) - at(a));  // twice the area, along the normal
    sum[a] += n, sum[b] += n, sum[c] += n;
  }
  std::vector<float> normals;
  normals.reserve(3 * sum.size());
  for (const Vec3& n : sum) {
    const Vec3 u = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::UnitZ();
    normals.insert(normals.end(), {float(u.x()), float(u.y()), float(u.z())});
  }
  return normals;
}

SpringTransform PlaceSpring(const Shape& s, const mech::Pose& from, const mech::Pose& to) {
  const Vec3 a = from * s.point1, d = to * s.point2 - a;
  const double length = d.norm();
  const Eigen::Quaterniond q =
      length > 0 ? Eigen::Quaterniond::FromTwoVectors(Vec3::UnitY(), d) : Eigen::Quaterniond::Identity();
  return {a, q, length};
}

}  // namespace mechflow::graphics
