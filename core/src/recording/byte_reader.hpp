// Reads a recording's bytes with every size checked against what is left: a value, a text or a
// count that runs past the end is a RecordingError naming the file, the byte and what was being
// read, never a read out of bounds.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

#include "softstep/recording.hpp"

namespace softstep::recording {

class ByteReader {
 public:
  ByteReader(const std::string& bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  template <class T>
  T get(const char* what) {
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  std::string text(std::size_t size, const char* what) {
    need(size, what);
    std::string t = bytes_.substr(at_, size);
    at_ += size;
    return t;
  }
  std::string text(const char* what) { return text(get<std::uint32_t>(what), what); }
  bool at_end() const { return at_ == bytes_.size(); }
  std::size_t offset() const { return at_; }
  // Fails unless `size` more bytes are there (to check a count before allocating for it).
  void need(std::size_t size, const char* what) const {
    if (size > bytes_.size() - at_)
      throw RecordingError(name_ + ": truncated at byte " + std::to_string(at_) + " (reading " +
                           what + ": " + std::to_string(size) + " bytes, " +
                           std::to_string(bytes_.size() - at_) + " left)");
  }

 private:
  const std::string& bytes_;
  const std::string& name_;
  std::size_t at_ = 0;
};

}  // namespace softstep::recording
