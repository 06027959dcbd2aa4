// Scene generators: the dispatch by `type` and the expansion of the `generators` list.
#include "io/generators.h"

#include "io/fabric_generator.h"
#include "io/yarn_generator.h"

#include <string>
#include <vector>

namespace fibra {
namespace {

using json_reader::Json;

struct Generator {
  const char* type;
  GeneratorExpand expand;
};

// Every generator by its `type`.
constexpr Generator kGenerators[] = {
    {"yarn", expandYarn},
    {"woven_fabric", expandWovenFabric},
};

GeneratorExpand generatorOf(const Json& spec, const std::string& path) {
  if (!spec.is_object()) json_reader::fail(path, json_reader::typeMismatch("an object", spec));
  if (!spec.contains("type")) json_reader::fail(path + ".type", "required field missing");
  const std::string type = json_reader::asString(spec.at("type"), path + ".type");
  std::string known;
  for (const Generator& g : kGenerators) {
    if (type == g.type) return g.expand;
    known += (known.empty() ? "" : ", ") + std::string(g.type);
  }
  json_reader::fail(path + ".type", "unknown value \"" + json_reader::shown(type) +
                                        "\" (expected one of: " + known + ")");
}

}  // namespace

Json& sceneList(Json& scene, const char* key) {
  if (!scene.contains(key)) scene[key] = Json::array();
  Json& list = scene[key];
  if (!list.is_array()) json_reader::fail(key, json_reader::typeMismatch("an array", list));
  return list;
}

Json expandGenerators(const Json& scene) {
  if (!scene.is_object() || !scene.contains("generators")) return scene;
  Json out = scene;
  out.erase("generators");
  json_reader::forEachItem(scene.at("generators"), "generators",
                           [&](const Json& spec, const std::string& path) {
                             generatorOf(spec, path)(spec, path, out);
                           });
  return out;
}

}  // namespace fibra
