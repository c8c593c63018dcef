#include "scene/scene_loader.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "scene/scene_builder.h"
#include "scene/scene_overrides.h"
#include "scene/toml_reader.h"

namespace periflex {

const std::vector<std::string>& scene_integrator_names() {
  // the schema's explicit integrators and the implicit ones the solver may add
  static const std::vector<std::string> names = {"symplectic_euler", "verlet", "rk4", "dopri54",
                                                 "implicit_euler", "trapezoidal", "newmark", "hht",
                                                 "generalized_alpha"};
  return names;
}

SceneDef load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  // read the whole file; a missing or unreadable file is bad input too
  SourceLocation where;
  where.file = path;
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InputError(where, "is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(where, "cannot read the scene file");
  return parse_scene(text.str(), path, overrides);
}

SceneDef parse_scene(std::string_view toml_text, const std::string& display_path,
                     const std::vector<std::string>& overrides) {
  ReadContext context;
  context.file = display_path;

  // TOML syntax first: toml++ reports the line and column of the first error
  toml::table root = parse_toml_located(toml_text, display_path);

  // overrides change the tree, so their values are checked like the file's
  apply_overrides(root, overrides, context);

  SceneDef scene = build_scene(root, context, std::filesystem::path(display_path).stem().string());
  scene.path = display_path;
  return scene;
}

}  // namespace periflex
