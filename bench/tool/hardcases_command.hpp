#pragma once

#include <string>

#include "tool/arguments.hpp"
#include "tool/view_recorder.hpp"

namespace softstep::tool {

struct HardcasesOptions {
  std::string simd = "best";
  std::string solver = "iterative";
  int substeps = WorldSettings{}.substeps;
  std::string only;  // non-empty: only the cases whose name contains it
  bool quick = false;
  std::string view_dir;  // non-empty: a viewer page per case goes there
  ViewLimits limits;
};

// Declares `softstep hardcases` and its options on the tool's app.
CLI::App* add_hardcases_command(CLI::App& app, HardcasesOptions& options);
// softstep hardcases [--simd W] [--solver S] [--substeps N] [--case TEXT] [--quick]: runs the
// hard-case suite and prints its table.
int hardcases_command(const HardcasesOptions& options);

}  // namespace softstep::tool
