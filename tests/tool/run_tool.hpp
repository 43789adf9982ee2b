// Runs the softstep tool as a user would (its path comes from CMake) and captures what it
// printed, so the tests check the command line itself: options, help, errors, files.
#pragma once

#include <string>

namespace softstep::tool_test {

struct ToolRun {
  int exit_code = -1;
  std::string out, err;
};

// `arguments` is appended to the tool's path as one shell word list (quote paths yourself).
ToolRun run_tool(const std::string& arguments);

// A fresh empty folder under the test's temporary directory.
std::string scratch_dir(const std::string& name);

std::string read_text(const std::string& path);

}  // namespace softstep::tool_test
