// The scene file's sections, each read into its Defs (internal to the loader). Readers check
// the form of the text: types, unknown and missing fields, value names (enums), table syntax
// and order; validateScene then checks ranges and cross-references on the whole SceneDef.
#pragma once

#include "io/json_reader.h"
#include "engine/scene.h"

#include <map>
#include <string>

namespace fibra::scene_sections {

using json_reader::Json;
using Tables = std::map<std::string, Table>;

// scene_loader.cpp
MaterialDef readMaterial(const Json& j, const std::string& path);
FibreDef readFibre(const Json& j, const std::string& path);
GroupDef readGroup(const Json& j, const std::string& path);
StepDef readStep(const Json& j, const std::string& path);
// `fibres`: the scene's, for probes at a fibre's "end".
OutputDef readOutput(const Json& j, const std::string& path, const std::vector<FibreDef>& fibres);

// scene_loader_motion.cpp
Tables readTables(const Json& j, const std::string& path);
BcDef readBc(const Json& j, const std::string& path, const Tables& tables);
LoadDef readLoad(const Json& j, const std::string& path, const Tables& tables);
ToolDef readTool(const Json& j, const std::string& path, const Tables& tables);
ContactDef readContact(const Json& j, const std::string& path);
StabilisationDef readStabilisation(const Json& j, const std::string& path);
SolverDef readSolver(const Json& j, const std::string& path);

// scene_loader_contact.cpp
std::vector<LevelDef> readLevels(const Json& j, const std::string& path);
ContactPairDef readContactPair(const Json& j, const std::string& path);
// A step's `forced_normals` object: {"direction": D, "allowance": A (mm, default 0)} into
// StepDef::forcedNormal (unit) and forcedAllowance; errors name the field.
void readForcedNormals(const Json& j, const std::string& path, StepDef& s);

}  // namespace fibra::scene_sections
