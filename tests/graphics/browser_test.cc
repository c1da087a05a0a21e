// The animation in a real browser (issue 16, item 5): headless Chromium
// (Debian's, software WebGL) opens the file written by `mechflow run
// --animate`; the page's test interface seeks to given times and reports
// every body's world transform, the share of non-background pixels and the
// colour at each body's origin, and the errors it saw. The transforms must
// equal the poses the results give, to 1e-6.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

namespace mechflow {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const char* Chromium() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (fs::exists(path)) return path;
  return nullptr;
}

// What the page wrote into <pre id="mechflow-test"> after seeking to `times`.
std::string BrowserReport(const fs::path& html, const std::string& times) {
  const std::string command = std::string(Chromium()) +
                              " --headless=new --no-sandbox --use-gl=angle --use-angle=swiftshader"
                              " --enable-unsafe-swiftshader --window-size=800,600 --virtual-time-budget=5000"
                              " --dump-dom 'file://" + html.string() + "#test=" + times + "' 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return "";
  std::string dom;
  char buffer[65536];
  for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) dom.append(buffer, n);
  pclose(pipe);
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
  std::istringstream in(json.substr(at + key.size() + 4, json.find(']', at) - at - key.size() - 4));
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::stod(item));
  return out;
}

// The rows of a results CSV, by time.
std::vector<std::vector<double>> Rows(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    std::string f;
    while (std::getline(fields, f, ',')) row.push_back(std::stod(f));
    rows.push_back(row);
  }
  return rows;
}

TEST(BrowserTest, TheQuarterCarsAnimationShowsTheSimulatedPoses) {
  ASSERT_NE(Chromium(), nullptr) << "Chromium is missing: scripts/install-deps.sh installs Debian's chromium";
  const fs::path dir = fs::path(::testing::TempDir()) / "browser_quarter_car";
  fs::remove_all(dir);
  const auto run = testing::RunMechflow("run " + std::string(MECHFLOW_SOURCE_DIR) +
                                        "/diagrams/examples/quarter_car.xml --out " + dir.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("quarter_car.html (801 frames of 3 bodies"));

  const std::vector<double> times = {0, 2.5, 5.05, 8};
  const std::string report = BrowserReport(dir / "quarter_car.html", "0,2.5,5.05,8");
  ASSERT_FALSE(report.empty()) << "the page wrote no test report";
  EXPECT_THAT(report, HasSubstr("\"errors\":[]"));

  // columns: time, road, wheel, body, ... (quarter_car.xml's <log>s)
  const auto rows = Rows(dir / "quarter_car.csv");
  std::size_t from = 0;
  for (const double t : times) {
    from = report.find("{\"t\":", from + 1);
    ASSERT_NE(from, std::string::npos);
    const std::vector<double>& row = rows.at(static_cast<std::size_t>(std::lround(t / 0.002)));
    ASSERT_NEAR(row[0], t, 1e-12);
    const char* labels[] = {"car.Footprint", "car.Wheel", "car.Body"};
    for (int b = 0; b < 3; ++b) {
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
    const std::size_t share = report.find("\"share\":", from);
    EXPECT_GT(std::stod(report.substr(share + 8)), 0.02);
  }
}

}  // namespace
}  // namespace mechflow
