// The glTF file holds only float32 (graphics/gltf.h): every file
// `mechflow run --gltf` writes passes the Khronos glTF-Validator, or the run
// writes none, says why (the shape, body or spring and the time) and exits 1
// with its CSV written. Keyframe times count from the run's start, so a late
// start keeps them apart; frames float32 cannot tell apart merge.

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

namespace mechflow {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

class GltfTest : public ::testing::Test {
 protected:
  GltfTest() {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::path(::testing::TempDir()) / ("mechflow_gltf_" + test + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~GltfTest() override { fs::remove_all(dir_); }

  // Runs a diagram named d of `mechanism` (inside <mechanism name="m">) and
  // `run` (solver and output) with --gltf.
  testing::CommandOutcome Run(const std::string& mechanism, const std::string& run) {
    const fs::path xml = dir_ / "d.xml";
    std::ofstream(xml) << "<diagram name='d'><mechanism name='m'>" << mechanism
                       << "<sensor name='z' kind='position' body='B' component='z'/></mechanism>" << run
                       << "</diagram>\n";
    return testing::RunMechflow("run " + xml.string() + " --gltf --out " + (dir_ / "out").string());
  }
  fs::path Glb() const { return dir_ / "out" / "d.glb"; }
  fs::path Csv() const { return dir_ / "out" / "d.csv"; }

  // The validator's counts and messages (tests/graphics/validate_gltf.js).
  static std::string Validate(const fs::path& glb) {
    const std::string command =
        "node " + std::string(MECHFLOW_SOURCE_DIR) + "/tests/graphics/validate_gltf.js " + glb.string();
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return "";
    std::string text;
    char buffer[4096];
    for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) text.append(buffer, n);
    pclose(pipe);
    return text;
  }

  fs::path dir_;
};

// A body B moved along z by its joint as z = `z` (an expression of t), with a box of edge `edge`.
std::string Driven(const std::string& z, const std::string& edge = "0.1") {
  return "<body name='B' mass='1' inertia='1 1 1'/>"
         "<joint name='j' type='generalized' body1='Base0' body2='B'><et type='tt' axis='0 0 1' value='" + z +
         "'/></joint><shape type='box' body='B' size='" + edge + " 0.1 0.1' name='block'/>";
}
const char* kOneSecond = "<solver t_end='1'/><output interval='0.01'><log signal='m.z'/></output>";
const char* kClean = "{\"errors\":0,\"warnings\":0,\"infos\":0,";

TEST_F(GltfTest, AShapeBeyondFloat32WritesNoFileAndSaysWhich) {
  const auto run = Run(Driven("t", "1e39"), kOneSecond);  // finite as a double, infinite as a float
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  EXPECT_THAT(run.err, HasSubstr("no glTF file"));
  EXPECT_THAT(run.err, HasSubstr(":1: shape 'block': a vertex: beyond float32's range"));
  EXPECT_THAT(run.err, HasSubstr("scale the model"));
  EXPECT_FALSE(fs::exists(Glb()));
  EXPECT_TRUE(fs::exists(Csv()));  // the rest of the run is written
  EXPECT_THAT(run.out, HasSubstr("d.csv"));
}

TEST_F(GltfTest, ABodyBeyondFloat32WritesNoFileAndSaysWhenAndWhich) {
  const auto run = Run(Driven("1e39*t"), kOneSecond);  // beyond 3.4028e38 from t = 0.35 on
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  EXPECT_THAT(run.err, HasSubstr("body 'm.B' at t = 0.35"));
  EXPECT_THAT(run.err, HasSubstr("its translation: beyond float32's range"));
  EXPECT_FALSE(fs::exists(Glb()));
  EXPECT_TRUE(fs::exists(Csv()));
}

TEST_F(GltfTest, ASpringLongerThanFloat32HoldsWritesNoFile) {
  // both ends within float32, the spring between them 4e38 long
  const std::string mechanism =
      Driven("2e38") +
      "<body name='C' mass='1' inertia='1 1 1'/>"
      "<joint name='k' type='generalized' body1='Base0' body2='C'><et type='tt' axis='0 0 1' value='-2e38'/></joint>"
      "<shape type='sphere' body='C'/><shape type='spring' body='B' body2='C' name='coil'/>";
  const auto run = Run(mechanism, kOneSecond);
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  EXPECT_THAT(run.err, HasSubstr("spring 'coil' at t = 0 s: its scale: beyond float32's range"));
  EXPECT_FALSE(fs::exists(Glb()));
}

// float32 steps by 1 at 1e7: the frames 0.01 s apart would share times.
TEST_F(GltfTest, ALateStartKeepsTheKeyframesApart) {
  const auto run = Run(Driven("t - 1e7"), "<solver t_start='1e7' t_end='10000001'/>"
                                          "<output interval='0.01'><log signal='m.z'/></output>");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("d.glb (101 frames of 1 bodies"));
  EXPECT_THAT(Validate(Glb()), HasSubstr(kClean));
}

// Far from the start float32 cannot tell 1e6 from 1e6 + 0.01 s, though the
// frames are 1/120 s apart: the earlier merges into the later.
TEST_F(GltfTest, FramesFloat32CannotTellApartMerge) {
  const auto run = Run(Driven("t"), "<solver t_end='1000000.01'/>"
                                    "<output interval='100000'><log signal='m.z'/></output>");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("d.glb (11 frames of 1 bodies"));
  EXPECT_THAT(run.out, HasSubstr("1 frame merged into the next"));
  EXPECT_THAT(Validate(Glb()), HasSubstr(kClean));
}

TEST_F(GltfTest, AnOrdinaryRunMergesNothing) {
  const auto run = Run(Driven("t"), kOneSecond);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("d.glb (101 frames of 1 bodies"));
  EXPECT_THAT(run.out, Not(HasSubstr("merged")));
  EXPECT_THAT(Validate(Glb()), HasSubstr(kClean));
}

}  // namespace
}  // namespace mechflow
