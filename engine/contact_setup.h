// Contact parameters resolved from the scene, in one place (defaults: docs/CONTACT.md and
// components/contact_params.h).
#pragma once

#include "components/contact_params.h"
#include "engine/scene.h"

namespace fibra {

// Resolves `def` for `fibres`. Throws SceneError for negative distances or angles, or
// thetaParallel > thetaCross.
ContactParams resolveContactParams(const FibreStore& fibres, const ContactDef& def);

}  // namespace fibra
