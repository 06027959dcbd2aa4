#include "io/json_reader.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <set>

namespace fibra::json_reader {
namespace {

// Nesting deeper than this is refused: a scene needs 5 levels or so; each level costs its
// path here, so 100 000 nested brackets (a 200 KB file) took gigabytes before.
constexpr size_t kMaxDepth = 64;

// Tracks the path of the value being parsed, to name a repeated key. nlohmann keeps the last
// of repeated keys silently; a scene must not lose a field that way.
class DuplicateKeys {
 public:
  bool event(Json::parse_event_t event, const Json& parsed) {
    using E = Json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        if (frames_.size() >= kMaxDepth)
          fail(pathHere(), "nested deeper than " + std::to_string(kMaxDepth) +
                               " levels of objects and arrays");
        frames_.push_back({pathHere(), event == E::array_start, 0, "", {}});
        break;
      case E::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second && duplicate_.empty()) duplicate_ = join(f.path, f.key);
        break;
      }
      case E::object_end:
      case E::array_end:
        frames_.pop_back();
        advance();
        break;
      case E::value:
        advance();
        break;
    }
    return true;
  }
  const std::string& duplicate() const { return duplicate_; }
  std::string current() const { return pathHere(); }  // the field being read

 private:
  struct Frame {
    std::string path;
    bool array;
    int index;
    std::string key;
    std::set<std::string> keys;
  };
  std::string pathHere() const {
    if (frames_.empty()) return "";
    const Frame& f = frames_.back();
    return f.array ? f.path + "[" + std::to_string(f.index) + "]" : join(f.path, f.key);
  }
  void advance() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  std::vector<Frame> frames_;
  std::string duplicate_;
};

// Edit distance, for suggestions.
size_t distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string listOf(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

Json parse(const std::string& text) {
  DuplicateKeys keys;
  Json j;
  try {
    j = Json::parse(
        text, [&keys](int, Json::parse_event_t e, Json& parsed) { return keys.event(e, parsed); },
        true, true);
  } catch (const Json::parse_error& e) {
    // nlohmann: "[json.exception.parse_error.101] parse error at line 3, column 6: syntax ..."
    const std::string what = e.what();
    const size_t at = what.find("parse error at ");
    const size_t colon = what.find(": ", at == std::string::npos ? 0 : at);
    if (at == std::string::npos || colon == std::string::npos)
      throw SceneError("byte " + std::to_string(e.byte) + ": malformed JSON: " + what);
    throw SceneError(what.substr(at + 15, colon - at - 15) +
                     ": malformed JSON: " + what.substr(colon + 2));
  } catch (const Json::out_of_range& e) {
    // nlohmann: "[json.exception.out_of_range.406] number overflow parsing '1e999'"
    const std::string what = e.what();
    const size_t quote = what.find('\'');
    const std::string literal =
        quote == std::string::npos ? "" : what.substr(quote + 1, what.size() - quote - 2);
    fail(keys.current(), "the number " + shown(literal) +
                             " is out of range (a double's magnitude is at most 1.8e308)");
  }
  if (!keys.duplicate().empty()) fail(keys.duplicate(), "duplicate field");
  return j;
}

void fail(const std::string& path, const std::string& what) {
  throw SceneError(path.empty() ? what : path + ": " + what);
}

std::string shown(const std::string& value) {
  return value.size() > 40 ? value.substr(0, 37) + "..." : value;
}

std::string typeMismatch(const char* expected, const Json& got) {
  std::string s = std::string("expected ") + expected + ", got ";
  if (got.is_object()) return s + "an object";
  if (got.is_array()) return s + "an array";
  if (got.is_null()) return s + "null";
  const std::string value = shown(got.dump());
  const char* kind = got.is_string() ? "a string" : got.is_boolean() ? "a boolean" : "the number";
  return s + kind + " " + value;
}

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string closestKey(const std::string& key, const std::vector<std::string>& known) {
  std::string best;
  size_t bestDistance = std::max<size_t>(2, key.size() / 3) + 1;
  for (const std::string& k : known) {
    const size_t d = distance(key, k);
    if (d < bestDistance) {
      bestDistance = d;
      best = k;
    }
  }
  return best;
}

Fields::Fields(const Json& json, std::string path, std::vector<std::string> known,
               std::string context)
    : json_(json), path_(std::move(path)) {
  if (!json_.is_object()) fail(path_, typeMismatch("an object", json_));
  for (const auto& item : json_.items()) {
    if (std::find(known.begin(), known.end(), item.key()) != known.end()) continue;
    std::string what = "unknown field";
    if (!context.empty()) what += " for " + context;
    const std::string close = closestKey(item.key(), known);
    what += close.empty() ? " (known fields: " + listOf(known) + ")"
                          : " (did you mean '" + close + "'?)";
    fail(join(path_, item.key()), what);
  }
}

const Json& Fields::at(const char* key) const {
  if (!has(key)) fail(path(key), "required field missing");
  return json_.at(key);
}

double Fields::number(const char* key, double fallback) const {
  return has(key) ? number(key) : fallback;
}
double Fields::number(const char* key) const { return asNumber(at(key), path(key)); }
int Fields::integer(const char* key, int fallback) const {
  return has(key) ? integer(key) : fallback;
}
int Fields::integer(const char* key) const { return asInteger(at(key), path(key)); }

bool Fields::boolean(const char* key, bool fallback) const {
  if (!has(key)) return fallback;
  const Json& j = at(key);
  if (!j.is_boolean()) fail(path(key), typeMismatch("true or false", j));
  return j.get<bool>();
}

std::string Fields::string(const char* key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}
std::string Fields::string(const char* key) const { return asString(at(key), path(key)); }
Vec3 Fields::vec3(const char* key, const Vec3& fallback) const {
  return has(key) ? vec3(key) : fallback;
}
Vec3 Fields::vec3(const char* key) const { return asVec3(at(key), path(key)); }

void Fields::badChoice(const char* key, const std::string& got,
                       const std::vector<std::string>& names) const {
  std::string what = "unknown value \"" + shown(got) + "\" (expected one of: " + listOf(names) + ")";
  fail(path(key), what);
}

namespace {

void dumpInto(const Json& j, int indent, std::string& out) {
  const bool flat = j.is_primitive() ||
                    std::none_of(j.begin(), j.end(), [](const Json& e) { return e.is_structured(); });
  if (j.is_primitive() || j.empty()) {
    out += j.dump();
    return;
  }
  if (j.is_array() && flat) {
    out += '[';
    for (size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + j[i].dump();
    out += ']';
    return;
  }
  const std::string pad(size_t(indent + 2), ' ');
  out += j.is_array() ? "[\n" : "{\n";
  bool first = true;
  for (auto it = j.begin(); it != j.end(); ++it) {
    out += (first ? "" : ",\n") + pad;
    if (j.is_object()) out += Json(it.key()).dump() + ": ";
    dumpInto(*it, indent + 2, out);
    first = false;
  }
  out += "\n" + std::string(size_t(indent), ' ') + (j.is_array() ? "]" : "}");
}

}  // namespace

std::string readableDump(const Json& json) {
  std::string out;
  dumpInto(json, 0, out);
  return out + "\n";
}

double asNumber(const Json& j, const std::string& path) {
  if (!j.is_number()) fail(path, typeMismatch("a number", j));
  return j.get<double>();
}

int asInteger(const Json& j, const std::string& path) {
  if (!j.is_number()) fail(path, typeMismatch("an integer", j));
  const double v = j.get<double>();
  if (v != std::floor(v) || std::abs(v) > INT_MAX) fail(path, typeMismatch("an integer", j));
  return int(v);
}

std::string asString(const Json& j, const std::string& path) {
  if (!j.is_string()) fail(path, typeMismatch("a string", j));
  return j.get<std::string>();
}

Vec3 asVec3(const Json& j, const std::string& path) {
  if (!j.is_array()) fail(path, typeMismatch("a vector [x, y, z]", j));
  if (j.size() != 3)
    fail(path, "expected a vector [x, y, z], got " + std::to_string(j.size()) + " values");
  Vec3 v;
  for (int i = 0; i < 3; ++i) v(i) = asNumber(j[i], path + "[" + std::to_string(i) + "]");
  return v;
}

void forEachItem(const Json& json, const std::string& path,
                 const std::function<void(const Json&, const std::string&)>& fn) {
  if (!json.is_array()) fail(path, typeMismatch("an array", json));
  for (size_t i = 0; i < json.size(); ++i) fn(json[i], path + "[" + std::to_string(i) + "]");
}

}  // namespace fibra::json_reader
