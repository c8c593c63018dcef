// What a drawn marker of the model stands for: the model records one per joint, driver and
// attachment (model/system_model.h), the snapshot carries it to the renderer (Snapshot::Marker).
#pragma once

namespace periflex {

enum class MarkerKind { kRevolute, kTranslational, kRigid, kLink, kDriver, kAttachment };

}  // namespace periflex
