#include "core/json_object.hpp"

#include "voronoimesh/core/errors.hpp"

#include <cmath>

namespace vm::detail {

std::string brief(const nlohmann::json& v) {
  std::string s = v.dump();
  constexpr size_t max_len = 40;
  return s.size() <= max_len ? s : s.substr(0, max_len - 3) + "...";
}

JsonObject::JsonObject(const nlohmann::json& j, std::string source, std::string where)
    : json_(j), source_(std::move(source)), where_(std::move(where)) {
  if (!json_.is_object())
    fail("expected a JSON object { ... }, got " + brief(json_));
}

void JsonObject::fail(const std::string& problem) const {
  throw InvalidInput(located(source_, where_.empty() ? problem : where_ + ": " + problem));
}

void JsonObject::allow_only(std::initializer_list<std::string_view> allowed) const {
  for (const auto& item : json_.items()) {
    bool known = false;
    std::string list;
    for (std::string_view a : allowed) {
      known = known || item.key() == a;
      list += (list.empty() ? "" : ", ") + std::string(a);
    }
    if (!known) fail("unknown key '" + item.key() + "' (expected " + list + ")");
  }
}

const nlohmann::json& JsonObject::at(const std::string& key) const {
  auto it = json_.find(key);
  if (it == json_.end()) fail("missing key '" + key + "'");
  return *it;
}

double JsonObject::as_number(const nlohmann::json& v, const std::string& what) const {
  if (!v.is_number()) fail("'" + what + "' must be a number, got " + brief(v));
  const double d = v.get<double>();
  // JSON has no NaN and nlohmann 3.11 refuses overflowing literals; checked all the
  // same, since a non-finite number would only surface much later, mid-sampling.
  if (!std::isfinite(d)) fail("'" + what + "' must be a finite number, got " + brief(v));
  return d;
}

Vec3 JsonObject::as_vec3(const nlohmann::json& v, const std::string& what) const {
  if (!v.is_array() || v.size() != 3)
    fail("'" + what + "' must be an array of 3 numbers, got " + brief(v));
  Vec3 p;
  for (int a = 0; a < 3; ++a)
    p[a] = as_number(v[size_t(a)], what + "[" + std::to_string(a) + "]");
  return p;
}

double JsonObject::number(const std::string& key) const { return as_number(at(key), key); }

Vec3 JsonObject::vec3(const std::string& key) const { return as_vec3(at(key), key); }

std::string JsonObject::string(const std::string& key) const {
  const auto& v = at(key);
  if (!v.is_string()) fail("'" + key + "' must be a string, got " + brief(v));
  return v.get<std::string>();
}

JsonObject JsonObject::object(const std::string& key) const {
  const auto& v = at(key);
  if (!v.is_object()) fail("'" + key + "' must be an object { ... }, got " + brief(v));
  return JsonObject(v, source_, where_.empty() ? key : where_ + "." + key);
}

} // namespace vm::detail
