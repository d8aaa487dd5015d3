#pragma once
/// @file json_object.hpp
/// Typed, checked access to one object of a JSON scene, so that every mistake in
/// a scene becomes one InvalidInput line naming the file, the place and the key.

#include "voronoimesh/core/types.hpp"

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <string>
#include <string_view>

namespace vm::detail {

/// A JSON object inside the text `source`, at the place `where` ("" for the root,
/// "phase 3", "domain"...). All accessors throw InvalidInput on a missing or
/// ill-typed key.
class JsonObject {
public:
  /// Throws unless `j` is an object.
  JsonObject(const nlohmann::json& j, std::string source, std::string where);

  /// Throws naming the first key not in `allowed` (typos would otherwise be ignored).
  void allow_only(std::initializer_list<std::string_view> allowed) const;

  bool has(const std::string& key) const { return json_.contains(key); }
  /// The value of a key that must be present.
  const nlohmann::json& at(const std::string& key) const;

  double number(const std::string& key) const;
  std::string string(const std::string& key) const;
  Vec3 vec3(const std::string& key) const;
  /// The nested object under `key`, placed at "<where>.<key>" for its errors.
  JsonObject object(const std::string& key) const;

  /// Checks that `v` (found under `what`, e.g. "points[2]") is a finite number.
  double as_number(const nlohmann::json& v, const std::string& what) const;
  /// Checks that `v` is an array of three finite numbers.
  Vec3 as_vec3(const nlohmann::json& v, const std::string& what) const;

  const nlohmann::json& json() const { return json_; }
  const std::string& source() const { return source_; }
  /// "<source>: <where>", the place of this object in messages.
  std::string place() const { return where_.empty() ? source_ : source_ + ": " + where_; }

  /// Throws InvalidInput "<source>: <where>: <problem>".
  [[noreturn]] void fail(const std::string& problem) const;

private:
  const nlohmann::json& json_;
  std::string source_, where_;
};

/// Deepest nesting of arrays and objects parse_json() accepts. Scenes nest a few
/// levels; a bound keeps every walk over a value (dumping it, destroying it)
/// shallow, whatever a file holds.
constexpr int kMaxJsonDepth = 64;

/// The JSON value of `text`, read from `source`. Throws InvalidInput
/// "<source>: malformed JSON at line L, column C: <reason>", "<source>: JSON
/// nested deeper than 64 levels at line L" or "<source>: key 'k' appears twice in
/// one object" (a later value would silently replace the first).
nlohmann::json parse_json(const std::string& text, const std::string& source);

/// A JSON value shortened for an error message: a number, or a string of at most
/// 40 characters, as written; an array or object by its size only (so a value
/// of any size or depth costs as little to describe).
std::string brief(const nlohmann::json& v);

} // namespace vm::detail
