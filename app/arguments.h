// Command-line values shared by fibra's commands. Bad usage throws std::invalid_argument, which
// the program reports with the command's usage line (exit 2).
#pragma once

#include <stdexcept>
#include <string>

namespace fibra::arguments {

// `text` as an integer >= 1; else "OPTION: expected a positive integer, got 'TEXT'".
inline int positiveInt(const std::string& text, const std::string& option) {
  size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || v < 1)
    throw std::invalid_argument(option + ": expected a positive integer, got '" + text + "'");
  return v;
}

}  // namespace fibra::arguments
