// A small argument reader for the softstep tool: --name value flags, each consumed once,
// with errors that say which flag and which value was wrong (the tool exits 2 on them).
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "softstep/world_settings.hpp"

namespace softstep::tool {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Arguments {
 public:
  explicit Arguments(std::span<char* const> args);
  // Positional words before the first flag (subcommand, scene name).
  std::vector<std::string> take_positionals();
  bool take_switch(const std::string& flag);
  std::string take_string(const std::string& flag, const std::string& fallback);
  std::string take_choice(const std::string& flag, const std::vector<std::string>& choices,
                          const std::string& fallback);
  long take_int(const std::string& flag, long fallback, long min, long max);
  // A comma-separated list of whole numbers, each in [min, max]: "1,2,4".
  std::vector<long> take_int_list(const std::string& flag, const std::string& fallback, long min,
                                  long max);
  double take_double(const std::string& flag, double fallback, double min, double max);
  bool has(const std::string& flag) const;
  // Throws UsageError naming any flag nobody took.
  void reject_leftovers() const;

 private:
  std::vector<std::string> words_;
  std::vector<bool> used_;
  int find(const std::string& flag) const;
  std::string value_of(const std::string& flag);
};

// "best", "scalar", "sse" or "avx2" (take_choice has checked it).
SimdWidth parse_simd(const std::string& name);

}  // namespace softstep::tool
