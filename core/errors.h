// Errors of scene input: a scene (file or SceneDef) that cannot be built.
#pragma once

#include <stdexcept>

namespace fibra {

// `what()` names the field path and what is wrong, e.g. "fibres[2].radius: must be > 0".
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace fibra
