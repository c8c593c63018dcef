// Where shaders/, assets/ and scenes/ are, so the program works from any current directory.
#pragma once

#include <string>

namespace periflex {

// $PERIFLEX_ROOT when set, else the source tree the program was built from
// (it holds shaders/, assets/ and scenes/).
std::string find_resource_root();

}  // namespace periflex
