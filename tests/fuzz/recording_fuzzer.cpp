// Feeds arbitrary bytes to the recording reader (replay_recording_bytes): a truncated or
// corrupted recording must end in a RecordingError, never a crash, a sanitizer report, or any
// other exception. Seeds in tests/fuzz/recording_corpus are small real recordings.
#include <cstddef>
#include <cstdint>
#include <string>

#include "softstep/recording.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    softstep::replay_recording_bytes(bytes, "fuzz.rec");
  } catch (const softstep::RecordingError&) {
    // The promised outcome for a bad file.
  }
  return 0;
}
