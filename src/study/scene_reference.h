// The head shared by study and sweep files: which scene they run, under which name, with which
// `--set` overrides. Paths in those files are relative to the file itself, so a study folder can
// be moved as a whole.
#pragma once

#include <string>
#include <vector>

namespace periflex {

class TableReader;

struct SceneReference {
  std::string name;                    // default: the file's stem
  std::string scene_path;              // resolved against the file's folder
  std::vector<std::string> overrides;  // "key=value"
};

// `written` as a path: itself when absolute, else relative to the folder of `file`.
std::string path_beside(const std::string& file, const std::string& written);

// Reads `name`, `scene` (required) and `set` from the file's head table.
SceneReference read_scene_reference(TableReader& head, const std::string& file);

}  // namespace periflex
