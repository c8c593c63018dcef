#include "cli/frame_sink.h"

#include "cli/gui_command.h"
#include "core/error.h"

namespace periflex {

#ifndef PERIFLEX_WITH_HEADLESS
std::unique_ptr<FrameSink> make_frame_sink(const RunOptions&, const std::string&,
                                           std::shared_ptr<const SceneGeometry>) {
  throw InputError({"command line", 0, 0, "--render"},
                   "this build has no off-screen renderer (configured with -DPERIFLEX_HEADLESS=OFF)");
}
#endif

}  // namespace periflex
