// Files for the recording tests: a path in the temporary directory that no other test process
// uses, a file's bytes, and the check that bad bytes are refused with a given message.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "softstep/recording.hpp"

namespace softstep::test {

inline std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("softstep_recording_test_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

inline std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Replaying `bytes` must throw a RecordingError whose message holds `message`.
inline void expect_replay_error(const std::string& bytes, const std::string& name,
                                const std::string& message) {
  try {
    replay_recording_bytes(bytes, name);
    ADD_FAILURE() << "replayed";
  } catch (const RecordingError& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

// The first `size` bytes of a recording must be refused as cut short: truncated, without its
// end record, or (cut inside the signature) not a recording at all.
inline void expect_cut_refused(const std::string& bytes, std::size_t size) {
  SCOPED_TRACE(size);
  try {
    replay_recording_bytes(bytes.substr(0, size), "cut.rec");
    ADD_FAILURE() << "replayed";
  } catch (const RecordingError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("cut.rec", 0), 0) << m;
    EXPECT_TRUE(m.find("truncated") != std::string::npos ||
                m.find("without its end record") != std::string::npos ||
                m.find("not a softstep recording") != std::string::npos)
        << m;
  }
}

}  // namespace softstep::test
