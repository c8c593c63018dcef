// `periflex check SCENE`: parse, validate and build the model, then print what it contains
// and what may go wrong, without stepping.
#pragma once

#include <string>
#include <vector>

namespace periflex {

int check_command(const std::string& scene_path, const std::vector<std::string>& overrides);

}  // namespace periflex
