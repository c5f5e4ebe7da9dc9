// glTF files on the command line: a bad file or --camera is one line on stderr and exit code 2.
#include "tests/support/test_paths.h"
#include <sys/wait.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace gb {

namespace {

std::string corpus(const std::string& name) { return std::string(GBLENS_SOURCE_DIR) + "/tests/data/gltf/" + name; }

}  // namespace

// The command line: a bad file is one line on stderr and exit code 2; a bad --camera too.
TEST(Gltf, CommandLineExitsTwoOnBadFilesAndCameras) {
  auto run = [](const std::string& args, std::string& err) {
    std::string log = ::testing::TempDir() + "gblens_gltf_cli.txt";
    int status = std::system((std::string(GBLENS_BINARY) + " " + args + " 2>" + log + " >/dev/null").c_str());
    std::ifstream in(log);
    std::stringstream ss;
    ss << in.rdbuf();
    err = ss.str();
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  std::string err;
  EXPECT_EQ(run("info '" + corpus("invalid/node_cycle.gltf") + "'", err), 2);
  EXPECT_NE(err.find("node_cycle.gltf: node 1: is part of a node cycle"), std::string::npos) << err;
  EXPECT_EQ(run("render '" + corpus("valid/cameras.gltf") + "' --camera 3 --size 8x8 -o /dev/null", err), 2);
  EXPECT_NE(err.find("--camera 3"), std::string::npos) << err;
  EXPECT_EQ(run("info '" + corpus("valid/cameras.gltf") + "'", err), 0);
}

}  // namespace gb
