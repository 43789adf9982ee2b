// Reading one JSON object of a scene file field by field, with the JSON path of every field
// at hand: a wrong type, a missing field, an unknown key or a value the API refuses becomes a
// SceneFileError naming the file, the path and the value as the file wrote it.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "softstep/scene_file.hpp"

namespace softstep::scene {

using nlohmann::json;

// The file being read: its name for messages and its root, to quote values by path.
struct Source {
  std::string name;
  const json* root = nullptr;
};

// "file: /bodies/3/mass = -1: why".
[[noreturn]] void fail(const Source& source, const std::string& path, const std::string& why);

class ObjectReader {
 public:
  // Fails unless `object` is a JSON object.
  ObjectReader(const Source& source, const json& object, std::string path);

  bool has(const char* key) const;
  double number(const char* key);  // required
  double number(const char* key, double fallback);
  int integer(const char* key, int fallback);
  bool boolean(const char* key, bool fallback);
  std::string text(const char* key);  // required
  std::string text(const char* key, const std::string& fallback);
  Eigen::Vector3d vec3(const char* key);  // required
  Eigen::Vector3d vec3(const char* key, const Eigen::Vector3d& fallback);
  Eigen::Matrix3d mat3(const char* key, const Eigen::Matrix3d& fallback);  // rows
  Quaternion quaternion(const char* key, const Quaternion& fallback);      // [w, x, y, z]
  // "rigid", "free", {"hertz": F, "damping_ratio": Z}, or in absolute units
  // {"absolute_stiffness": K, "absolute_damping": C} (either may be left out: 0).
  Spring spring(const char* key, const Spring& fallback);
  // A body by its index in the file's "bodies" array (required).
  BodyId body(const char* key, const std::vector<BodyId>& bodies);
  // The elements of an array (required unless `optional`; a missing optional one is empty).
  const json& array(const char* key, bool optional = false);
  const json& object(const char* key);  // an empty object when missing

  // Rejects any key no read asked for: a misspelt field must not be silently ignored.
  void no_other_keys() const;

  // The JSON pointer of a key of this object ("~" and "/" in the key escaped as RFC 6901 says).
  std::string path_of(const std::string& key) const;
  const Source& source() const { return source_; }

  // Runs an API call; an InvalidArgument it throws becomes a SceneFileError at this object's
  // path plus the field the API named ("BodyDef.mass" -> ".../mass").
  template <class Call>
  auto call(Call&& api_call) -> decltype(api_call()) {
    try {
      return api_call();
    } catch (const SceneFileError&) {
      throw;
    } catch (const InvalidArgument& e) {
      refused(e);
    }
  }

 private:
  const json* find(const char* key);  // marks the key read; nullptr when missing
  const json& required(const char* key);
  [[noreturn]] void wrong_type(const char* key, const char* expected) const;
  [[noreturn]] void refused(const InvalidArgument& e) const;

  Source source_;
  const json& object_;
  std::string path_;
  std::vector<std::string> read_;
};

}  // namespace softstep::scene
