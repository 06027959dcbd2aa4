#include "app/study_knob.h"

#include <cctype>

namespace fibra::study {

using Json = nlohmann::json;

std::vector<PathStep> parsePath(const std::string& field) {
  const auto bad = [&] {
    return std::invalid_argument("--vary: expected a field path such as fibres[0].elements, got '" +
                                 field + "'");
  };
  std::vector<PathStep> path;
  size_t i = 0;
  while (i < field.size()) {
    const size_t end = field.find_first_of(".[]", i);
    const std::string key = field.substr(i, end - i);
    if (key.empty()) throw bad();
    path.push_back({key});
    i = end == std::string::npos ? field.size() : end;
    while (i < field.size() && field[i] == '[') {
      const size_t close = field.find(']', i);
      const std::string digits = field.substr(i + 1, close - i - 1);
      if (close == std::string::npos || digits.empty() || digits.size() > 9 ||
          digits.find_first_not_of("0123456789") != std::string::npos)
        throw bad();
      path.push_back({"", size_t(std::stoul(digits))});
      i = close + 1;
    }
    if (i < field.size() && (field[i] != '.' || i + 1 == field.size())) throw bad();
    if (i < field.size()) ++i;
  }
  if (path.empty()) throw bad();
  return path;
}

Json& slot(Json& root, const std::vector<PathStep>& path, const std::string& field,
           const std::string& scene) {
  Json* at = &root;
  std::string walked;
  for (size_t k = 0; k < path.size(); ++k) {
    const PathStep& s = path[k];
    const bool last = k + 1 == path.size();
    const std::string here = s.key.empty() ? walked + "[" + std::to_string(s.index) + "]"
                                           : (walked.empty() ? s.key : walked + "." + s.key);
    const bool exists = s.key.empty() ? at->is_array() && s.index < at->size()
                                      : at->is_object() && (at->contains(s.key) || last);
    if (!exists)
      throw InputError(
          "--vary " + field + ": " + scene + " has no '" + here + "'" +
          (at->is_object() || at->is_array() ? "" : " ('" + walked + "' holds a value)"));
    at = s.key.empty() ? &(*at)[s.index] : &(*at)[s.key];
    walked = here;
  }
  return *at;
}

Json parseValue(const std::string& text) {
  try {
    const Json j = Json::parse(text);
    if (j.is_number() || j.is_boolean()) return j;
  } catch (const Json::exception&) {
  }
  return text;
}

std::string folderName(const std::string& field, const std::string& value) {
  std::string name = field + "=" + value;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) &&
        std::string("._-=+[]").find(c) == std::string::npos)
      c = '_';
  return name;
}

}  // namespace fibra::study
