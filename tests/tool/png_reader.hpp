// Reads the PNG files a browser writes as screenshots (8-bit RGB or RGBA, not interlaced), so
// that a test can look at the pixels.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace softstep::tool_test {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // width x height x 3, rows top first
  const std::uint8_t* pixel(int x, int y) const { return &rgb[(std::size_t(y) * width + x) * 3]; }
};

// Throws std::runtime_error for anything it cannot read.
Image read_png(const std::string& path);

}  // namespace softstep::tool_test
