#pragma once
// Running the mechflow command in tests as a user would: the exit code and
// what it printed, in a folder of this test process (CTest runs tests in
// parallel).

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace mechflow::testing {

struct CommandOutcome {
  int exit_code = -1;
  std::string out, err;
};

inline std::string ReadFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `PREFIX mechflow ARGS` through the shell (PREFIX: e.g. "mpirun -n 2 ")
// with stdout and stderr captured and no input.
inline CommandOutcome RunMechflow(const std::string& args, const std::string& prefix = "") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / ("mechflow_command_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string command = prefix + std::string(MECHFLOW_BINARY) + " " + args + " >" + (dir / "out").string() +
                              " 2>" + (dir / "err").string() + " </dev/null";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ReadFile(dir / "out"), ReadFile(dir / "err")};
}

}  // namespace mechflow::testing
