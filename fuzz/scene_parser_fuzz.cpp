// libFuzzer target for the scene loader, its budget and its warnings: any byte string must either
// load or be refused with InputError. Anything else -- another exception, a crash, a sanitizer report, a hang -- is a bug.
//
// Leading lines of the form "#set key.path=value" (TOML comments, so the rest still parses)
// are also passed as --set overrides, so the override code is fuzzed with the same input.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_budget.h"
#include "scene/scene_loader.h"
#include "scene/scene_warnings.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);

  // collect the override lines at the top
  std::vector<std::string> overrides;
  size_t at = 0;
  while (text.substr(at, 5) == "#set ") {
    const size_t end = text.find('\n', at);
    const size_t stop = end == std::string_view::npos ? text.size() : end;
    overrides.emplace_back(text.substr(at + 5, stop - at - 5));
    if (end == std::string_view::npos) break;
    at = end + 1;
  }

  // bad input must be reported, never crash
  try {
    // the budget and the warnings scan the grid: they must stay bounded on any scene that loads
    const periflex::SceneDef scene = periflex::parse_scene(text, "fuzz.toml", overrides);
    periflex::check_scene_budget(scene);
    periflex::scene_warnings(scene);
  } catch (const periflex::InputError&) {
  }
  return 0;
}
