// fibra's umbrella header: the embedding API (World, SceneDef, StepReport), scene files and the
// output writers. Consumers of the installed package write #include <fibra/fibra.h>
// (docs/EMBEDDING.md).
#pragma once

#include "fibra/version.h"
#include "engine/world.h"
#include "io/outputs.h"
#include "io/scene_loader.h"
