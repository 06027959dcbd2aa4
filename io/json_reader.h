// JSON reading for the scene loader (internal): parsing with duplicate-key detection, and typed
// access to an object's fields that names the field path in every error. Every error is a
// SceneError "PATH: what is wrong"; the loader prefixes the file name.
#pragma once

#include "components/fibres.h"
#include "engine/scene.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <initializer_list>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace fibra::json_reader {

using Json = nlohmann::json;

// Parses text (// and /* */ comments allowed). Malformed text: "line L, column C: malformed
// JSON: ..."; a key repeated in one object: "PATH.key: duplicate field".
Json parse(const std::string& text);

[[noreturn]] void fail(const std::string& path, const std::string& what);

// A value as shown in a message: itself, or its first 37 characters and "..." when longer than 40.
std::string shown(const std::string& value);

// "expected a number, got a string ("abc")"
std::string typeMismatch(const char* expected, const Json& got);

// "a.b" from "a" and "b"; the root's fields have no prefix.
std::string join(const std::string& path, const std::string& key);

// The closest of `known` to `key` when the difference is small (a typo), else "".
std::string closestKey(const std::string& key, const std::vector<std::string>& known);

// An object's fields. The constructor checks that `json` is an object whose keys are all among
// `known` (else "PATH.key: unknown field (did you mean 'x'?)"); `context` (e.g. "a helix
// geometry") qualifies that message when the known keys depend on a type.
class Fields {
 public:
  Fields(const Json& json, std::string path, std::vector<std::string> known,
         std::string context = "");

  const std::string& path() const { return path_; }
  std::string path(const std::string& key) const { return join(path_, key); }
  bool has(const char* key) const { return json_.contains(key); }
  const Json& at(const char* key) const;  // required field

  double number(const char* key, double fallback) const;
  double number(const char* key) const;  // required
  int integer(const char* key, int fallback) const;
  int integer(const char* key) const;  // required
  bool boolean(const char* key, bool fallback) const;
  std::string string(const char* key, const std::string& fallback) const;
  std::string string(const char* key) const;  // required
  Vec3 vec3(const char* key, const Vec3& fallback) const;
  Vec3 vec3(const char* key) const;  // required

  // A string field that must be one of `choices` (T deduced from the fallback; required
  // fields name it: choice<Kind>(...)).
  template <class T>
  using Choices = std::type_identity_t<std::initializer_list<std::pair<const char*, T>>>;
  template <class T>
  T choice(const char* key, Choices<T> choices, T fallback) const {
    if (!has(key)) return fallback;
    return pick<T>(key, choices);
  }
  template <class T>
  T choice(const char* key, Choices<T> choices) const {
    at(key);
    return pick<T>(key, choices);
  }

 private:
  template <class T>
  T pick(const char* key, Choices<T> choices) const {
    const std::string s = string(key);
    std::vector<std::string> names;
    for (const auto& [name, value] : choices) {
      if (s == name) return value;
      names.push_back(name);
    }
    badChoice(key, s, names);
  }
  [[noreturn]] void badChoice(const char* key, const std::string& got,
                              const std::vector<std::string>& names) const;

  const Json& json_;
  std::string path_;
};

// JSON text for people: objects and arrays of objects or arrays one entry a line (2-space
// indent), arrays of numbers, strings and booleans on one line; numbers as nlohmann writes them
// (the shortest decimal that reads back to the same double).
std::string readableDump(const Json& json);

// Typed readers of a value at `path`.
double asNumber(const Json& j, const std::string& path);
int asInteger(const Json& j, const std::string& path);
std::string asString(const Json& j, const std::string& path);
Vec3 asVec3(const Json& j, const std::string& path);

// Calls fn(item, "PATH[i]") for every item of an array (an error if `json` is not one).
void forEachItem(const Json& json, const std::string& path,
                 const std::function<void(const Json&, const std::string&)>& fn);

}  // namespace fibra::json_reader
