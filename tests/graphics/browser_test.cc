// The animation in a real browser (what a user sees, not what we wrote): headless
// Chromium (Debian's, software WebGL) opens the files `mechflow run` writes.
// - NAME.html: the page's test interface seeks to given times and reports
//   every body's world transform, the share of non-background pixels, the
//   colour at each body's origin, what hovering there names, the traced path,
//   the plot's cursor, the changing shapes' vertices, and the errors it saw.
// - NAME.glb: a page of the test's own loads it with three.js's GLTFLoader
//   and plays its animation with an AnimationMixer; the Khronos glTF-Validator
//   (node) checks the file.
// Poses must equal the simulation's results to 1e-6.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "graphics/encoding.h"
#include "tests/cli/mechflow_command.h"
#include "tests/graphics/hostile_names.h"
#include "tests/numbers.h"

namespace mechflow {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using mechflow::testing::kPi;

const char* Chromium() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (fs::exists(path)) return path;
  return nullptr;
}

std::string Output(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return "";
  std::string text;
  char buffer[65536];
  for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) text.append(buffer, n);
  pclose(pipe);
  return text;
}

// What the page `url` wrote into <pre id="mechflow-test">.
std::string BrowserReport(const std::string& url) {
  const std::string dom = Output(std::string(Chromium()) +
                                 " --headless=new --no-sandbox --use-gl=angle --use-angle=swiftshader"
                                 " --enable-unsafe-swiftshader --window-size=800,600 --virtual-time-budget=5000"
                                 " --dump-dom '" + url + "' 2>/dev/null");
  const std::string open = "<pre id=\"mechflow-test\">";
  const std::size_t start = dom.find(open);
  if (start == std::string::npos) return "";
  return dom.substr(start + open.size(), dom.find("</pre>", start) - start - open.size());
}

// The numbers of the array after "key": in `json` from `from` on.
std::vector<double> ArrayAfter(const std::string& json, const std::string& key, std::size_t from = 0) {
  std::vector<double> out;
  std::size_t at = json.find("\"" + key + "\":[", from);
  if (at == std::string::npos) return out;
  at += key.size() + 4;
  std::istringstream in(json.substr(at, json.find(']', at) - at));
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::stod(item));
  return out;
}

// The number after "key": in `json` from `from` on.
double NumberAfter(const std::string& json, const std::string& key, std::size_t from = 0) {
  const std::size_t at = json.find("\"" + key + "\":", from);
  return at == std::string::npos ? NAN : std::stod(json.substr(at + key.size() + 3));
}

// The results CSV: its header's names and its rows.
struct Csv {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  int Column(const std::string& name) const {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return static_cast<int>(i);
    return -1;
  }
  // the row of time t on a grid of `interval`
  const std::vector<double>& At(double t, double interval) const {
    const std::vector<double>& row = rows.at(static_cast<std::size_t>(std::lround(t / interval)));
    EXPECT_NEAR(row[0], t, 1e-9);
    return row;
  }
};
Csv ReadCsv(const fs::path& path) {
  Csv csv;
  std::ifstream in(path);
  std::string line, field;
  std::getline(in, line);
  for (std::istringstream header(line); std::getline(header, field, ',');) csv.names.push_back(field);
  while (std::getline(in, line)) {
    std::vector<double> row;
    for (std::istringstream fields(line); std::getline(fields, field, ',');) row.push_back(std::stod(field));
    csv.rows.push_back(row);
  }
  return csv;
}

// Runs an example into a fresh folder of its own: one per test and example,
// since CTest runs the tests of this file side by side.
fs::path RunExample(const std::string& name, const std::string& options = "") {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path dir = fs::path(::testing::TempDir()) / ("browser_" + test + "_" + name);
  fs::remove_all(dir);
  const auto run = testing::RunMechflow("run " + std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name +
                                        ".xml " + options + " --out " + dir.string());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return dir;
}

class BrowserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NE(Chromium(), nullptr) << "Chromium is missing: scripts/install-deps.sh installs Debian's chromium";
  }
};

TEST_F(BrowserTest, TheQuarterCarsAnimationShowsTheSimulatedPoses) {
  const fs::path dir = RunExample("quarter_car");
  const std::vector<double> times = {0, 2.5, 5.05, 8};
  const std::string report =
      BrowserReport("file://" + (dir / "quarter_car.html").string() + "#test=0,2.5,5.05,8&trace=car.Body&plot=body");
  ASSERT_FALSE(report.empty()) << "the page wrote no test report";
  EXPECT_THAT(report, HasSubstr("\"frames\":801,"));
  EXPECT_THAT(report, HasSubstr("\"errors\":[]"));

  const Csv csv = ReadCsv(dir / "quarter_car.csv");
  const int body_column = csv.Column("body");
  ASSERT_GT(body_column, 0);
  std::size_t from = 0;
  for (const double t : times) {
    from = report.find("{\"t\":", from + 1);
    ASSERT_NE(from, std::string::npos);
    const std::vector<double>& row = csv.At(t, 0.002);
    const char* labels[] = {"car.Footprint", "car.Wheel", "car.Body"};
    for (int b = 0; b < 3; ++b) {  // columns road, wheel, body after time
      const std::vector<double> pose = ArrayAfter(report, labels[b], from);
      ASSERT_EQ(pose.size(), 7u) << labels[b];
      EXPECT_NEAR(pose[0], 0.0, 1e-6);
      EXPECT_NEAR(pose[1], 0.0, 1e-6);
      EXPECT_NEAR(pose[2], row[1 + b], 1e-6) << labels[b] << " at t = " << t;
      EXPECT_NEAR(pose[6], 1.0, 1e-6);  // no rotation
    }
    // not blank, and the car body (red) where the camera sees its origin
    const std::vector<double> colour = ArrayAfter(report, "colour", report.find("\"car.Body\":{\"share\"", from));
    ASSERT_EQ(colour.size(), 3u);
    EXPECT_GT(colour[0], 90);
    EXPECT_GT(colour[0], 2 * colour[1]);
    EXPECT_GT(colour[0], 2 * colour[2]);
    EXPECT_GT(NumberAfter(report, "share", from), 0.02);
    // hovering there names the shape and its body
    EXPECT_NE(report.find("\"car.Body\":\"car body on car.Body\"", from), std::string::npos);
    // the trace of the body's origin reaches its position now, the plot's cursor the logged value
    const std::vector<double> end = ArrayAfter(report, "traceEnd", from);
    ASSERT_EQ(end.size(), 3u);
    EXPECT_NEAR(end[2], row[body_column], 1e-6);
    EXPECT_EQ(NumberAfter(report, "traced", from), std::lround(t / 0.01) + 1);  // frames 0.01 s apart
    const std::vector<double> cursor = ArrayAfter(report, "cursor", from);
    ASSERT_EQ(cursor.size(), 2u);
    EXPECT_NEAR(cursor[0], t, 1e-9);
    EXPECT_NEAR(cursor[1], row[body_column], 1e-6);
  }
}

// The plot draws the logged signal at every output row, not at the frames
// (1/120 s apart): the tension mechanism with friction hits its end stop
// between two frames, and a plot of the frames held 172.9 N where the
// results peak at 195.04 N, and read 0.27 N at t = 0.131 s where they have 195 N.
TEST_F(BrowserTest, ThePlotHoldsThePeaksBetweenFrames) {
  const fs::path dir = RunExample("tension_mechanism", "--set Friction=1");
  const Csv csv = ReadCsv(dir / "tension_mechanism.csv");
  const int force = csv.Column("contact force");
  ASSERT_GT(force, 0);
  std::size_t peak = 0;
  for (std::size_t r = 0; r < csv.rows.size(); ++r)
    if (csv.rows[r][force] > csv.rows[peak][force]) peak = r;
  const double t_peak = csv.rows[peak][0], between = csv.rows[peak][0] + 0.0005;  // halfway to the next row
  const std::string report = BrowserReport("file://" + (dir / "tension_mechanism.html").string() + "#test=0.131," +
                                           std::to_string(between) + "&plot=contact%20force");
  ASSERT_FALSE(report.empty()) << "the page wrote no test report";
  EXPECT_THAT(report, HasSubstr("\"errors\":[]"));
  // the cursor: the row's value at a row's time, the rows interpolated between them
  const std::vector<double> at_row = ArrayAfter(report, "cursor", report.find("{\"t\":"));
  ASSERT_EQ(at_row.size(), 2u);
  EXPECT_NEAR(at_row[1], csv.At(0.131, 0.001)[force], 1e-9);
  const std::vector<double> halfway = ArrayAfter(report, "cursor", report.find("{\"t\":", report.find("{\"t\":") + 1));
  ASSERT_EQ(halfway.size(), 2u);
  EXPECT_NEAR(halfway[0], between, 1e-9);
  EXPECT_NEAR(halfway[1], (csv.rows[peak][force] + csv.rows[peak + 1][force]) / 2, 1e-6) << "t_peak " << t_peak;
  const std::size_t plotted = report.find("\"plotted\":");
  ASSERT_NE(plotted, std::string::npos) << report.substr(0, 300);
  EXPECT_EQ(NumberAfter(report, "points", plotted), static_cast<double>(csv.rows.size()));
  EXPECT_EQ(NumberAfter(report, "max", plotted), csv.rows[peak][force]);  // the same double: float64 in the page
  EXPECT_GT(csv.rows[peak][force], 190.0);
}

// Text as the page's DOM dump shows it: '<', '>' and '&' as entities.
std::string DumpedText(const std::string& text) {
  std::string out;
  for (const char c : text) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

// Names holding "<!--<script>" and "</script>" neither end nor hide the
// page's data script: the viewer runs and shows the body under its name.
TEST_F(BrowserTest, ThePageShowsBodiesWhoseNamesHoldScriptTags) {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path dir = fs::path(::testing::TempDir()) / ("browser_" + test);
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "d.xml") << testing::kHostileNamesDiagram;
  const auto run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string report = BrowserReport("file://" + (dir / "out" / "d.html").string() + "#test=0.5");
  ASSERT_FALSE(report.empty()) << "the page did not run its viewer";
  EXPECT_THAT(report, HasSubstr("\"errors\":[]"));
  const std::string label = DumpedText(testing::kHostileBodyLabel);
  const std::vector<double> pose = ArrayAfter(report, label);
  ASSERT_EQ(pose.size(), 7u) << report.substr(0, 400);
  EXPECT_NEAR(pose[2], 0.5, 1e-6);  // z = t
  EXPECT_THAT(report, HasSubstr("\"" + label + "\":\"" + DumpedText("</script> <!-- &")));  // hovering names the box
}

// UM's molecule: along the unit direction d(u, v) the surface lies at
// r = |dx|^n + |dy|^n + |dz|^n, n = mdeg, which the control script changes.
TEST_F(BrowserTest, TheMoleculesSurfaceFollowsMdeg) {
  const fs::path dir = RunExample("molecule");
  // the shape's versions: from mdeg's first change (0.01 s) every 0.07 s (at
  // least 1/15 s apart on the 0.01 s grid); between them the viewer interpolates
  const std::string report = BrowserReport("file://" + (dir / "molecule.html").string() + "#test=0.43,1.27");
  ASSERT_FALSE(report.empty());
  EXPECT_THAT(report, HasSubstr("\"errors\":[]"));
  const Csv csv = ReadCsv(dir / "molecule.csv");
  std::size_t from = 0;
  std::vector<double> degrees;
  for (const double t : {0.43, 1.27}) {
    from = report.find("{\"t\":", from + 1);
    const double n = csv.At(t, 0.01)[csv.Column("mdeg")];
    degrees.push_back(n);
    const std::vector<double> x = ArrayAfter(report, "molecule", from);
    constexpr int nu = 32, nv = 16;  // samples "32 16"
    ASSERT_EQ(x.size(), 3u * (nu + 1) * (nv + 1));
    double worst = 0;
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) {
        const double u = 2 * kPi * i / nu, v = kPi * j / nv;
        const double d[3] = {std::sin(v) * std::cos(u), std::sin(v) * std::sin(u), std::cos(v)};
        const double r = std::pow(std::abs(d[0]), n) + std::pow(std::abs(d[1]), n) + std::pow(std::abs(d[2]), n);
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(x[3 * (j * (nu + 1) + i) + k] - r * d[k]));
      }
    EXPECT_LT(worst, 1e-5) << "at t = " << t << ", mdeg = " << n;
  }
  EXPECT_GT(std::abs(degrees[1] - degrees[0]), 1.0);  // the two times show different forms
}

// A page that loads `glb` with three.js's GLTFLoader, plays its animation
// to each of `times` and reports the transform of every node below the root
// (in mechflow's z-up frame) by name: x y z qx qy qz qw sx sy sz. The loader
// makes names property paths ("p.Rod" -> "pRod", blanks -> '_').
fs::path GltfPage(const fs::path& glb, const std::string& times) {
  const auto read = [](const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const fs::path three = fs::path(MECHFLOW_SOURCE_DIR) / "graphics/web/node_modules/three";
  const std::string bytes = read(glb);
  const fs::path page = glb.string() + ".test.html";
  std::ofstream(page) << "<!doctype html><html><body><pre id=\"mechflow-test\"></pre><script>"
                      << read(three / "build/three.min.js") << "</script><script>"
                      << read(three / "examples/js/loaders/GLTFLoader.js") << "</script><script>\n"
                      << "const glb = Uint8Array.from(atob('" << graphics::Base64(bytes.data(), bytes.size())
                      << "'), (c) => c.charCodeAt(0)).buffer;\n"
                      << "const out = document.getElementById('mechflow-test');\n"
                      << "new THREE.GLTFLoader().parse(glb, '', (gltf) => {\n"
                         "  const root = gltf.scene.children[0];\n"
                         "  const mixer = new THREE.AnimationMixer(gltf.scene);\n"
                         "  for (const clip of gltf.animations) mixer.clipAction(clip).play();\n"
                         "  const report = { clips: gltf.animations.map((c) => c.name), seen: [] };\n"
                         "  for (const t of [" << times << "]) {\n"
                         "    mixer.setTime(t);\n"
                         "    gltf.scene.updateMatrixWorld(true);\n"
                         "    const toZUp = root.matrixWorld.clone().invert();\n"
                         "    const nodes = {};\n"
                         "    for (const n of root.children) {\n"
                         "      const p = new THREE.Vector3(), q = new THREE.Quaternion(), s = new THREE.Vector3();\n"
                         "      toZUp.clone().multiply(n.matrixWorld).decompose(p, q, s);\n"
                         "      nodes[n.name] = [p.x, p.y, p.z, q.x, q.y, q.z, q.w, s.x, s.y, s.z];\n"
                         "    }\n"
                         "    report.seen.push({ t, nodes });\n"
                         "  }\n"
                         "  out.textContent = JSON.stringify(report);\n"
                         "}, (error) => { out.textContent = JSON.stringify({ error: String(error) }); });\n"
                      << "</script></body></html>\n";
  return page;
}

// The transform of `node` the glTF page reported at its i-th time.
std::vector<double> Node(const std::string& report, int i, const std::string& node) {
  std::size_t at = 0;
  for (int k = 0; k <= i; ++k) at = report.find("{\"t\":", at + 1);
  const std::vector<double> transform = ArrayAfter(report, node, at);
  EXPECT_EQ(transform.size(), 10u) << node << " in " << report.substr(0, 300);
  return transform.size() == 10u ? transform : std::vector<double>(10, NAN);
}

TEST_F(BrowserTest, TheGltfFileCarriesThePendulumsMotion) {
  const fs::path dir = RunExample("pendulum", "--gltf");
  const std::string report = BrowserReport("file://" + GltfPage(dir / "pendulum.glb", "0,0.9,1.8").string());
  ASSERT_THAT(report, HasSubstr("\"clips\":[\"motion\"]"));
  const Csv csv = ReadCsv(dir / "pendulum.csv");
  const std::vector<double> times = {0, 0.9, 1.8};  // frame times: rows 0.009 s apart
  for (int i = 0; i < 3; ++i) {
    const std::vector<double> rod = Node(report, i, "pRod");
    const double phi = csv.At(times[i], 0.001)[1];
    const double sign = rod[6] < 0 ? -1 : 1;  // q and -q are one rotation
    EXPECT_NEAR(sign * rod[3], std::sin(phi / 2), 1e-6) << "t = " << times[i];
    EXPECT_NEAR(sign * rod[6], std::cos(phi / 2), 1e-6);
    EXPECT_NEAR(std::hypot(rod[0], rod[1], rod[2]), 0.0, 1e-6);
  }
}

TEST_F(BrowserTest, TheGltfFileStretchesTheQuarterCarsSprings) {
  const fs::path dir = RunExample("quarter_car", "--gltf");
  const std::string report = BrowserReport("file://" + GltfPage(dir / "quarter_car.glb", "2.5,5.05").string());
  const Csv csv = ReadCsv(dir / "quarter_car.csv");
  for (int i = 0; i < 2; ++i) {
    const double t = i == 0 ? 2.5 : 5.05;
    const std::vector<double>& row = csv.At(t, 0.002);
    EXPECT_NEAR(Node(report, i, "carBody")[2], row[3], 1e-6);
    // the suspension spring from (0.4 0 0) on the wheel to (0.4 0 0.13) on the body
    const std::vector<double> spring = Node(report, i, "suspension_spring");
    EXPECT_NEAR(spring[8], row[3] + 0.13 - row[2], 1e-6);
    EXPECT_NEAR(spring[2], row[2], 1e-6);
  }
}

TEST(GltfValidatorTest, ExampleFilesHaveNoIssues) {
  for (const std::string name : {"quarter_car", "molecule", "pendulum"}) {
    const fs::path dir = RunExample(name, "--gltf");
    const std::string report = Output("node " + std::string(MECHFLOW_SOURCE_DIR) +
                                      "/tests/graphics/validate_gltf.js " + (dir / (name + ".glb")).string());
    EXPECT_THAT(report, HasSubstr("{\"errors\":0,\"warnings\":0,\"infos\":0,")) << name << ": " << report;
  }
}

}  // namespace
}  // namespace mechflow
