#include "tool/arguments.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace softstep::tool {

namespace {
// 1e+09 and 0.001, not std::to_string's 1000000000.000000 and 0.001000.
std::string readable(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}
}  // namespace

Arguments::Arguments(std::span<char* const> args)
    : words_(args.begin(), args.end()), used_(words_.size(), false) {}

std::vector<std::string> Arguments::take_positionals() {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < words_.size() && words_[i].rfind("--", 0) != 0; ++i) {
    if (used_[i]) continue;
    out.push_back(words_[i]);
    used_[i] = true;
  }
  return out;
}

int Arguments::find(const std::string& flag) const {
  for (std::size_t i = 0; i < words_.size(); ++i) {
    if (!used_[i] && words_[i] == flag) return static_cast<int>(i);
  }
  return -1;
}

bool Arguments::has(const std::string& flag) const {
  return find(flag) >= 0;
}

bool Arguments::take_switch(const std::string& flag) {
  const int i = find(flag);
  if (i < 0) return false;
  used_[static_cast<std::size_t>(i)] = true;
  return true;
}

std::string Arguments::value_of(const std::string& flag) {
  const int i = find(flag);
  const auto at = static_cast<std::size_t>(i);
  if (at + 1 >= words_.size() || words_[at + 1].rfind("--", 0) == 0) {
    throw UsageError(flag + " needs a value");
  }
  used_[at] = used_[at + 1] = true;
  return words_[at + 1];
}

std::string Arguments::take_string(const std::string& flag, const std::string& fallback) {
  return has(flag) ? value_of(flag) : fallback;
}

std::string Arguments::take_choice(const std::string& flag, const std::vector<std::string>& choices,
                                   const std::string& fallback) {
  const std::string v = take_string(flag, fallback);
  for (const auto& c : choices) {
    if (c == v) return v;
  }
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : "|") + c;
  throw UsageError(flag + " " + v + ": expected one of " + list);
}

long Arguments::take_int(const std::string& flag, long fallback, long min, long max) {
  if (!has(flag)) return fallback;
  const std::string v = value_of(flag);
  char* end = nullptr;
  errno = 0;
  const long n = std::strtol(v.c_str(), &end, 10);
  if (errno != 0 || end == v.c_str() || *end != '\0' || n < min || n > max) {
    throw UsageError(flag + " " + v + ": expected a whole number in [" + std::to_string(min) +
                     ", " + std::to_string(max) + "]");
  }
  return n;
}

std::vector<long> Arguments::take_int_list(const std::string& flag, const std::string& fallback,
                                           long min, long max) {
  const std::string text = take_string(flag, fallback);
  std::vector<long> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || errno != 0 || *end != '\0' || n < min || n > max) {
      throw UsageError(flag + " " + text + ": expected whole numbers in [" + std::to_string(min) +
                       ", " + std::to_string(max) + "] separated by commas");
    }
    out.push_back(n);
    at = comma + 1;
  }
  return out;
}

double Arguments::take_double(const std::string& flag, double fallback, double min, double max) {
  if (!has(flag)) return fallback;
  const std::string v = value_of(flag);
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (end == v.c_str() || *end != '\0' || !std::isfinite(x) || x < min || x > max) {
    throw UsageError(flag + " " + v + ": expected a number in [" + readable(min) + ", " +
                     readable(max) + "]");
  }
  return x;
}

void Arguments::reject_leftovers() const {
  for (std::size_t i = 0; i < words_.size(); ++i) {
    if (!used_[i]) throw UsageError("unknown argument " + words_[i]);
  }
}

SimdWidth parse_simd(const std::string& name) {
  if (name == "scalar") return SimdWidth::Scalar;
  if (name == "sse") return SimdWidth::Sse;
  if (name == "avx2") return SimdWidth::Avx2;
  return SimdWidth::Best;
}

}  // namespace softstep::tool
