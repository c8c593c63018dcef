// Builds the contacts a scene declares into the model (SystemModel::contacts), once the rigid
// bodies, flexible bodies and attachments exist.
#pragma once

#include "scene/scene_def.h"

namespace periflex {

struct SystemModel;

// One ContactElement per [[contact]]; nothing when the scene declares none. Throws InputError
// on a contact the model cannot build.
void build_contacts(const SceneDef& scene, SystemModel& model);

}  // namespace periflex
