#include "study/scene_reference.h"

#include <filesystem>

#include "scene/toml_reader.h"

namespace periflex {

std::string path_beside(const std::string& file, const std::string& written) {
  if (std::filesystem::path(written).is_absolute()) return written;
  return (std::filesystem::path(file).parent_path() / written).lexically_normal().string();
}

SceneReference read_scene_reference(TableReader& head, const std::string& file) {
  SceneReference out;
  out.name = head.string("name", std::filesystem::path(file).stem().string());
  out.scene_path = path_beside(file, head.required_string("scene"));
  out.overrides = head.strings("set");
  return out;
}

}  // namespace periflex
