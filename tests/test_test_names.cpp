// CTest registers each doctest case by name and cuts a name at ';' (a CMake list separator): such
// a case matches no test when CTest runs it and passes without running. No case name holds one.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

TEST_CASE("no test case name holds a semicolon, which CTest would cut") {
  const std::regex name(R"re(TEST_CASE\("([^"]*)")re");
  int cases = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FIBRA_SOURCE_DIR "/tests")) {
    if (entry.path().extension() != ".cpp") continue;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (std::sregex_iterator m(text.begin(), text.end(), name), end; m != end; ++m) {
      ++cases;
      CAPTURE(entry.path().filename().string());
      CHECK((*m)[1].str().find(';') == std::string::npos);
    }
  }
  CHECK(cases > 100);
}
