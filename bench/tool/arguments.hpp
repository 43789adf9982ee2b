// The softstep tool's options are declared with CLI11, which generates `--help` from them and
// names the option and the bad value in its errors. This header holds what the commands share
// on top of it: range checks that print their bounds readably, and the SIMD width names.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "softstep/world_settings.hpp"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace softstep::tool {

// A command line that parsed but does not make sense (an option of another scene, --zeta
// without --hertz): the tool prints it with the command's usage and exits 2, as for CLI11's own
// parse errors.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Accepts a finite number in [min, max] (CLI::Range lets NaN through, and prints 1e9 as
// 1000000000.000000).
CLI::Validator finite_in(double min, double max);
// Accepts a whole number in [min, max] (for each item of a comma-separated list too).
CLI::Validator whole_in(long min, long max);

// The SIMD width names the options accept.
const std::vector<std::string>& simd_names();
// "best", "scalar", "sse", "avx2" or "avx512" (the option's check has accepted it).
SimdWidth parse_simd(const std::string& name);
// WorldSettings::solver: "iterative", "direct-for-trees", "auto".
const std::vector<std::string>& solver_names();
SolverMode parse_solver(const std::string& name);

}  // namespace softstep::tool
