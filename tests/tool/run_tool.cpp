#include "run_tool.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

namespace softstep::tool_test {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {

// The folders this test process made, removed when it exits: every run of the suite made about
// twenty and left them (2,358 in one developer's /tmp). SOFTSTEP_KEEP_TEST_FILES=1 keeps them,
// to look at what a failing test wrote.
class ScratchFolders {
 public:
  void add(const std::filesystem::path& dir) {
    if (std::find(made_.begin(), made_.end(), dir) == made_.end()) made_.push_back(dir);
  }
  ~ScratchFolders() {
    if (std::getenv("SOFTSTEP_KEEP_TEST_FILES") != nullptr) return;
    std::error_code ignored;
    for (const auto& dir : made_) std::filesystem::remove_all(dir, ignored);
  }

 private:
  std::vector<std::filesystem::path> made_;
};

ScratchFolders& scratch_folders() {
  static ScratchFolders folders;
  return folders;
}

}  // namespace

// ctest runs tests as parallel processes: each gets folders of its own.
std::string scratch_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("softstep_tool_test_" + std::to_string(getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  scratch_folders().add(dir);
  return dir.string();
}

ToolRun run_tool(const std::string& arguments) {
  const std::string dir = scratch_dir("capture");
  const std::string out = dir + "/out", err = dir + "/err";
  const std::string command =
      std::string(SOFTSTEP_TOOL_PATH) + " " + arguments + " > " + out + " 2> " + err;
  const int status = std::system(command.c_str());
  ToolRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = read_text(out);
  run.err = read_text(err);
  return run;
}

}  // namespace softstep::tool_test
