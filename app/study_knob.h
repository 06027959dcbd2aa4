// fibra study's knob (app/study.cpp): the scene field a study varies, named by a JSON path such
// as "fibres[0].elements", and the values given for it on the command line.
#pragma once

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace fibra::study {

// Bad input found before anything runs or is written (exit 2).
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One step of a field path: an object's key, or an array's index (key empty).
struct PathStep {
  std::string key;
  size_t index = 0;
};

// "fibres[0].elements" -> {fibres, [0], elements}; std::invalid_argument for anything else.
std::vector<PathStep> parsePath(const std::string& field);

// The value at `path` in `root` (the JSON of the file `scene`). Every step but the last must
// exist; the last may be a key that the object lacks (a field left at its default), which is
// then added. InputError otherwise, naming `field` and the missing step.
nlohmann::json& slot(nlohmann::json& root, const std::vector<PathStep>& path,
                     const std::string& field, const std::string& scene);

// A value from the command line: a JSON number or boolean when it reads as one, else a string.
nlohmann::json parseValue(const std::string& text);

// DIR's folder name of a variant: FIELD=VALUE, characters other than letters, digits and
// . _ - = + [ ] made '_'.
std::string folderName(const std::string& field, const std::string& value);

}  // namespace fibra::study
