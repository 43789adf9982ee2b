#include "png_reader.hpp"

#include <zlib.h>

#include <cstdlib>
#include <stdexcept>

#include "run_tool.hpp"

namespace softstep::tool_test {

namespace {

std::uint32_t big_endian(const std::string& s, std::size_t at) {
  return (std::uint32_t(std::uint8_t(s[at])) << 24) |
         (std::uint32_t(std::uint8_t(s[at + 1])) << 16) |
         (std::uint32_t(std::uint8_t(s[at + 2])) << 8) | std::uint32_t(std::uint8_t(s[at + 3]));
}

// The Paeth predictor of the PNG specification (filter type 4).
int paeth(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

}  // namespace

Image read_png(const std::string& path) {
  const std::string file = read_text(path);
  if (file.size() < 8 || file.compare(1, 3, "PNG") != 0)
    throw std::runtime_error(path + ": not a PNG");
  Image image;
  int channels = 0;
  std::string compressed;
  for (std::size_t at = 8; at + 8 <= file.size();) {
    const std::uint32_t length = big_endian(file, at);
    const std::string type = file.substr(at + 4, 4);
    if (at + 12 + length > file.size()) throw std::runtime_error(path + ": truncated");
    if (type == "IHDR") {
      image.width = int(big_endian(file, at + 8));
      image.height = int(big_endian(file, at + 12));
      const int depth = std::uint8_t(file[at + 16]), colour = std::uint8_t(file[at + 17]);
      const int interlace = std::uint8_t(file[at + 20]);
      if (depth != 8 || (colour != 2 && colour != 6) || interlace != 0)
        throw std::runtime_error(path + ": only 8-bit RGB(A), not interlaced");
      channels = colour == 2 ? 3 : 4;
    } else if (type == "IDAT") {
      compressed += file.substr(at + 8, length);
    }
    at += 12 + length;
  }
  if (channels == 0) throw std::runtime_error(path + ": no IHDR");
  const std::size_t row = std::size_t(image.width) * channels;
  std::vector<std::uint8_t> raw((row + 1) * image.height);
  uLongf raw_size = uLongf(raw.size());
  if (uncompress(raw.data(), &raw_size, reinterpret_cast<const Bytef*>(compressed.data()),
                 uLong(compressed.size())) != Z_OK ||
      raw_size != raw.size())
    throw std::runtime_error(path + ": bad image data");
  std::vector<std::uint8_t> pixels(row * image.height);
  for (int y = 0; y < image.height; ++y) {
    const std::uint8_t filter = raw[y * (row + 1)];
    if (filter > 4) throw std::runtime_error(path + ": unknown row filter");
    const std::uint8_t* in = &raw[y * (row + 1) + 1];
    std::uint8_t* out = &pixels[y * row];
    const std::uint8_t* up = y > 0 ? out - row : nullptr;
    for (std::size_t i = 0; i < row; ++i) {
      const int a = i >= std::size_t(channels) ? out[i - channels] : 0;
      const int b = up ? up[i] : 0;
      const int c = up && i >= std::size_t(channels) ? up[i - channels] : 0;
      const int predicted = filter == 0   ? 0
                            : filter == 1 ? a
                            : filter == 2 ? b
                            : filter == 3 ? (a + b) / 2
                                          : paeth(a, b, c);
      out[i] = std::uint8_t(in[i] + predicted);
    }
  }
  image.rgb.resize(std::size_t(image.width) * image.height * 3);
  for (std::size_t p = 0; p < std::size_t(image.width) * image.height; ++p)
    for (int k = 0; k < 3; ++k) image.rgb[p * 3 + k] = pixels[p * channels + k];
  return image;
}

}  // namespace softstep::tool_test
