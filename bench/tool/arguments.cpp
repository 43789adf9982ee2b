#include "tool/arguments.hpp"

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace softstep::tool {

namespace {
std::string shortest(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", x);
  return b;
}
}  // namespace

CLI::Validator finite_in(double min, double max) {
  const std::string range = "[" + shortest(min) + ", " + shortest(max) + "]";
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(x) || x < min || x > max)
          return "value " + text + ": expected a number in " + range;
        return {};
      },
      range);
}

CLI::Validator whole_in(long min, long max) {
  const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const long n = std::strtol(text.c_str(), &end, 10);
        if (errno != 0 || end == text.c_str() || *end != '\0' || n < min || n > max)
          return "value " + text + ": expected a whole number in " + range;
        return {};
      },
      range);
}

const std::vector<std::string>& simd_names() {
  static const std::vector<std::string> names{"best", "scalar", "sse", "avx2", "avx512"};
  return names;
}

SimdWidth parse_simd(const std::string& name) {
  if (name == "scalar") return SimdWidth::Scalar;
  if (name == "sse") return SimdWidth::Sse;
  if (name == "avx2") return SimdWidth::Avx2;
  if (name == "avx512") return SimdWidth::Avx512;
  return SimdWidth::Best;
}

const std::vector<std::string>& solver_names() {
  static const std::vector<std::string> names{"iterative", "direct-for-trees", "auto"};
  return names;
}

SolverMode parse_solver(const std::string& name) {
  if (name == "direct-for-trees") return SolverMode::DirectForTrees;
  if (name == "auto") return SolverMode::Auto;
  return SolverMode::Iterative;
}

}  // namespace softstep::tool
