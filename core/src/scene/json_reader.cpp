#include "json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace softstep::scene {

namespace {

// The value at `path` as the file wrote it, or what stands for it when it is not there.
std::string quoted_value(const Source& source, const std::string& path) {
  if (source.root == nullptr) return "";
  std::string text;
  try {
    const json::json_pointer pointer(path);
    if (!source.root->contains(pointer)) return " (missing)";
    text = source.root->at(pointer).dump();
  } catch (const json::exception&) {
    return "";  // a path the API named that the file does not spell: quote nothing
  }
  if (text.size() > 80) text = text.substr(0, 77) + "...";
  return " = " + text;
}

}  // namespace

void fail(const Source& source, const std::string& path, const std::string& why) {
  throw SceneFileError(
      source.name, path.empty() ? "/" : path,
      source.name + ": " + (path.empty() ? "/" : path) + quoted_value(source, path) + ": " + why);
}

ObjectReader::ObjectReader(const Source& source, const json& object, std::string path)
    : source_(source), object_(object), path_(std::move(path)) {
  if (!object_.is_object()) fail(source_, path_, "expected an object");
}

std::string ObjectReader::path_of(const std::string& key) const {
  std::string escaped;
  for (char c : key) escaped += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return path_ + "/" + escaped;
}

bool ObjectReader::has(const char* key) const {
  return object_.contains(key);
}

const json* ObjectReader::find(const char* key) {
  read_.emplace_back(key);
  const auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

const json& ObjectReader::required(const char* key) {
  const json* v = find(key);
  if (v == nullptr) fail(source_, path_of(key), "missing: this field is required");
  return *v;
}

void ObjectReader::wrong_type(const char* key, const char* expected) const {
  fail(source_, path_of(key), std::string("expected ") + expected);
}

namespace {
// nlohmann reads a number too large for a double (1e999) as infinity: keep it, so the API
// rejects it with its own rule, as it would reject an infinite value from a program.
double as_number(const json& v) {
  return v.get<double>();
}
}  // namespace

double ObjectReader::number(const char* key) {
  const json& v = required(key);
  if (!v.is_number()) wrong_type(key, "a number");
  return as_number(v);
}

double ObjectReader::number(const char* key, double fallback) {
  return has(key) ? number(key) : fallback;
}

int ObjectReader::integer(const char* key, int fallback) {
  const json* v = find(key);
  if (v == nullptr) return fallback;
  if (!v->is_number_integer() || *v < std::numeric_limits<int>::min() ||
      *v > std::numeric_limits<int>::max())
    wrong_type(key, "a whole number");
  return v->get<int>();
}

bool ObjectReader::boolean(const char* key, bool fallback) {
  const json* v = find(key);
  if (v == nullptr) return fallback;
  if (!v->is_boolean()) wrong_type(key, "true or false");
  return v->get<bool>();
}

std::string ObjectReader::text(const char* key) {
  const json& v = required(key);
  if (!v.is_string()) wrong_type(key, "a string");
  return v.get<std::string>();
}

std::string ObjectReader::text(const char* key, const std::string& fallback) {
  return has(key) ? text(key) : fallback;
}

namespace {
bool numbers(const json& v, std::size_t n) {
  return v.is_array() && v.size() == n &&
         std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_number(); });
}
}  // namespace

Eigen::Vector3d ObjectReader::vec3(const char* key) {
  const json& v = required(key);
  if (!numbers(v, 3)) wrong_type(key, "[x, y, z]: three numbers");
  return {as_number(v[0]), as_number(v[1]), as_number(v[2])};
}

Eigen::Vector3d ObjectReader::vec3(const char* key, const Eigen::Vector3d& fallback) {
  return has(key) ? vec3(key) : fallback;
}

Eigen::Matrix3d ObjectReader::mat3(const char* key, const Eigen::Matrix3d& fallback) {
  const json* v = find(key);
  if (v == nullptr) return fallback;
  if (!v->is_array() || v->size() != 3 ||
      !std::all_of(v->begin(), v->end(), [](const json& row) { return numbers(row, 3); }))
    wrong_type(key, "[[xx, xy, xz], [yx, yy, yz], [zx, zy, zz]]: three rows of three numbers");
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = as_number((*v)[r][c]);
  return m;
}

Quaternion ObjectReader::quaternion(const char* key, const Quaternion& fallback) {
  const json* v = find(key);
  if (v == nullptr) return fallback;
  if (!numbers(*v, 4)) wrong_type(key, "[w, x, y, z]: four numbers");
  return Quaternion(as_number((*v)[0]), as_number((*v)[1]), as_number((*v)[2]), as_number((*v)[3]));
}

Spring ObjectReader::spring(const char* key, const Spring& fallback) {
  const json* v = find(key);
  if (v == nullptr) return fallback;
  if (v->is_string() && *v == "rigid") return Spring::rigid();
  if (v->is_string() && *v == "free") return Spring::free();
  if (!v->is_object())
    wrong_type(key,
               "\"rigid\", \"free\", {\"hertz\": F, \"damping_ratio\": Z} or "
               "{\"absolute_stiffness\": K, \"absolute_damping\": C}");
  ObjectReader fields(source_, *v, path_of(key));
  Spring s;
  if (fields.has("absolute_stiffness") || fields.has("absolute_damping")) {
    // Absolute units (spring.hpp); a spring without these keys is relative, as every file
    // written before them.
    s = Spring::absolute(fields.number("absolute_stiffness", 0.0),
                         fields.number("absolute_damping", 0.0));
  } else {
    s.hertz = fields.number("hertz");
    s.damping_ratio = fields.number("damping_ratio", 0.0);
  }
  fields.no_other_keys();
  return s;
}

BodyId ObjectReader::body(const char* key, const std::vector<BodyId>& bodies) {
  const json& v = required(key);
  if (!v.is_number_integer() || v < 0)
    wrong_type(key, "a body's index in \"bodies\" (a whole number from 0)");
  const auto index = v.get<std::uint64_t>();
  if (index >= bodies.size())
    fail(source_, path_of(key),
         "no such body: the file has " + std::to_string(bodies.size()) + " bodies");
  return bodies[index];
}

const json& ObjectReader::array(const char* key, bool optional) {
  static const json empty = json::array();
  const json* v = optional ? find(key) : &required(key);
  if (v == nullptr) return empty;
  if (!v->is_array()) wrong_type(key, "an array");
  return *v;
}

const json& ObjectReader::object(const char* key) {
  static const json empty = json::object();
  const json* v = find(key);
  return v == nullptr ? empty : *v;
}

void ObjectReader::no_other_keys() const {
  for (const auto& [key, value] : object_.items()) {
    if (std::find(read_.begin(), read_.end(), key) == read_.end())
      fail(source_, path_of(key), "unknown field");
  }
}

void ObjectReader::refused(const InvalidArgument& e) const {
  // The API names fields as "BodyDef.mass" or "WorldSettings.gravity": the part after the
  // struct's name is the file's key.
  std::string field = e.field();
  const std::size_t dot = field.find('.');
  if (dot != std::string::npos) field = field.substr(dot + 1);
  std::replace(field.begin(), field.end(), '.', '/');
  fail(source_, path_ + "/" + field, e.what());
}

}  // namespace softstep::scene
