#include "core/resources.h"

#include <cstdlib>
#include <filesystem>

namespace periflex {

std::string find_resource_root() {
  if (const char* env = std::getenv("PERIFLEX_ROOT"); env && *env) return env;
  return PERIFLEX_SOURCE_ROOT;
}

}  // namespace periflex
