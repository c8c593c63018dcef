// Where shaders/, assets/ and scenes/ are, so the program works from any current directory, from
// the build tree, and installed under any prefix (also one moved after installation).
#pragma once

#include <string>

namespace periflex {

// The first folder that holds shaders/, in this order:
//   1. share/periflex beside the program's own bin/ folder (an installed program, wherever its
//      prefix was installed or moved to);
//   2. $PERIFLEX_ROOT, when set;
//   3. the source tree the program was built from (a build-tree run).
// When none holds shaders/, the source tree (so messages name a path a user can check).
std::string find_resource_root();

// The choice find_resource_root makes for a program at `program_path`; `env_root` empty when
// $PERIFLEX_ROOT is unset.
std::string pick_resource_root(const std::string& program_path, const std::string& env_root,
                               const std::string& source_root);

}  // namespace periflex
