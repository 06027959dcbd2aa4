// Contact parameters resolved from the scene, in one place (defaults: docs/CONTACT.md and
// components/contact_params.h).
#pragma once

#include "components/contact_params.h"
#include "components/tools.h"
#include "engine/scene.h"

namespace fibra {

// Resolves `def` for `fibres`. Throws SceneError for negative distances or angles, or
// thetaParallel > thetaCross.
ContactParams resolveContactParams(const FibreStore& fibres, const ContactDef& def);

// Every contact parameter of the scene: detection (when fibre-fibre contact is on; throws as
// above), laws, penalties, loops (components/contact_params.h gives the defaults).
ContactParams resolveContact(const FibreStore& fibres, const SceneDef& scene);

// The tools and their zones with every fibre (initial penalty E_f R_f unless the scene gives one).
void buildTools(const SceneDef& scene, const FibreStore& fibres, const MaterialStore& materials,
                const ContactParams& params, ToolStore& tools, ToolZoneStore& zones);

}  // namespace fibra
