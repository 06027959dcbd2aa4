// Layering: no #include runs back up. The library's folders form layers,
//   core < components < systems < engine < io < app,
// and a file may include only headers of its own layer or of the layers below it
// (docs/ARCHITECTURE.md). Checked over every source file of the tree.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kLayers{"core", "components", "systems", "engine", "io", "app"};

int layerOf(const std::string& folder) {
  for (size_t i = 0; i < kLayers.size(); ++i)
    if (kLayers[i] == folder) return int(i);
  return -1;
}

struct Violation {
  std::string file, include;
};

// Every quoted include of a layer folder that names a higher layer.
std::vector<Violation> upwardIncludes(const fs::path& root) {
  std::vector<Violation> out;
  const std::regex include(R"re(^\s*#\s*include\s*"([a-z_]+)/[^"]+")re");
  for (const std::string& folder : kLayers) {
    if (!fs::is_directory(root / folder)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".h" && ext != ".cpp") continue;
      std::ifstream in(entry.path());
      for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (!std::regex_search(line, m, include)) continue;
        const int target = layerOf(m[1]);
        if (target > layerOf(folder))
          out.push_back({fs::relative(entry.path(), root).string(), line});
      }
    }
  }
  return out;
}

}  // namespace

TEST_CASE("no include runs back up the layers core < components < systems < engine < io < app") {
  const fs::path root = FIBRA_SOURCE_DIR;
  for (const std::string& folder : kLayers) CHECK(fs::is_directory(root / folder));
  const std::vector<Violation> v = upwardIncludes(root);
  for (const Violation& x : v) CAPTURE(x.file + ": " + x.include);
  for (const Violation& x : v) FAIL_CHECK(x.file << " includes upwards: " << x.include);
  CHECK(v.empty());
}

TEST_CASE("the layering check finds an include that runs back up") {
  const fs::path root = fs::temp_directory_path() / "fibra_layering_probe";
  fs::remove_all(root);
  fs::create_directories(root / "components");
  std::ofstream(root / "components" / "store.h") << "#pragma once\n#include \"engine/world.h\"\n";
  fs::create_directories(root / "engine");
  std::ofstream(root / "engine" / "world.h") << "#pragma once\n#include \"components/store.h\"\n";
  const std::vector<Violation> v = upwardIncludes(root);
  fs::remove_all(root);
  REQUIRE(v.size() == 1);
  CHECK(v[0].file == "components/store.h");
}
