#include "run_tool.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace softstep::tool_test {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// ctest runs tests as parallel processes: each gets folders of its own.
std::string scratch_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("softstep_tool_test_" + std::to_string(getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
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
