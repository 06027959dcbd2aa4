// Errors of input: a scene (file or SceneDef) that cannot be built; a checkpoint that cannot be
// restored.
#pragma once

#include <stdexcept>

namespace fibra {

// `what()` names the field path and what is wrong, e.g. "fibres[2].radius: must be > 0".
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `what()` says why a checkpoint was refused: not a checkpoint, truncated, corrupt, of another
// fibra version or of another scene (World::restoreCheckpoint).
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace fibra
