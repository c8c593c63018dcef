#include "scene/file_shape_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "scene/cloud_lattice.h"
#include "scene/dxf_shape.h"
#include "scene/image_shape.h"
#include "scene/point_file_reader.h"

namespace periflex {

namespace {

const std::vector<std::string> kFileShapeTypes = {"points", "image", "dxf"};

// Metres per unit of the file: `unit` by name or `scale` as a number, not both.
double read_scale(TableReader& in) {
  if (in.has("unit") && in.has("scale")) in.fail("scale", "give unit or scale, not both");
  if (in.has("unit")) {
    const std::string unit = in.choice("unit", {"m", "cm", "mm", "um"}, "m");
    return unit == "cm" ? 1e-2 : unit == "mm" ? 1e-3 : unit == "um" ? 1e-6 : 1.0;
  }
  return in.number("scale", 1.0, Sign::kPositive);
}

// The box that bounds the cloud's cells: what the body's area estimates and outline see.
ShapeDef bounding_box(const ParticleCloud& cloud, double dx) {
  ShapeDef box;
  box.kind = ShapeDef::Kind::kBox;
  const auto [xlo, xhi] = std::minmax_element(cloud.x.begin(), cloud.x.end());
  const auto [ylo, yhi] = std::minmax_element(cloud.y.begin(), cloud.y.end());
  box.center = Vec2(0.5 * (*xlo + *xhi), 0.5 * (*ylo + *yhi));
  box.width = *xhi - *xlo + dx;
  box.height = *yhi - *ylo + dx;
  return box;
}

// Leaves out the particles inside a hole.
void remove_holes(ParticleCloud& cloud, const std::vector<ShapeDef>& holes) {
  if (holes.empty()) return;
  long kept = 0;
  for (long k = 0; k < cloud.size(); ++k) {
    const Vec2 p(cloud.x[k], cloud.y[k]);
    if (std::any_of(holes.begin(), holes.end(), [&](const ShapeDef& h) { return h.contains(p); })) continue;
    cloud.x[kept] = cloud.x[k];
    cloud.y[kept] = cloud.y[k];
    cloud.volume[kept] = cloud.volume[k];
    cloud.no_fail[kept] = cloud.no_fail[k];
    cloud.line[kept] = cloud.line[k];
    ++kept;
  }
  for (auto* v : {&cloud.x, &cloud.y, &cloud.volume}) v->resize(kept);
  cloud.no_fail.resize(kept);
  cloud.line.resize(kept);
}

}  // namespace

bool is_file_shape(const toml::node& node) {
  const auto* table = node.as_table();
  if (table == nullptr) return false;
  const auto type = table->get_as<std::string>("type");
  return type != nullptr && std::find(kFileShapeTypes.begin(), kFileShapeTypes.end(), type->get()) != kFileShapeTypes.end();
}

std::string geometry_file(const FlexBodyDef& flex) {
  // geometry_source is "<type> <path>" (read_file_shape writes it so)
  const size_t space = flex.geometry_source.find(' ');
  return space == std::string::npos ? std::string() : flex.geometry_source.substr(space + 1);
}

std::string scene_relative_path(const std::string& scene_file, const std::string& file) {
  const std::filesystem::path path(file);
  if (path.is_absolute()) return file;
  const std::filesystem::path folder = std::filesystem::path(scene_file).parent_path();
  return folder.empty() ? file : (folder / path).string();
}

namespace {

void read_file_shape_at(TableReader& in, const std::string& path, const std::string& type, const LimitsDef& limits,
                        FlexBodyDef& flex);

}  // namespace

void read_file_shape(const ReadContext& context, const toml::node& node, const std::string& key,
                     const LimitsDef& limits, FlexBodyDef& flex) {
  TableReader in(context, *node.as_table(), key, "shape '" + key + "'");
  const std::string type = in.required_choice("type", kFileShapeTypes);
  const std::string file = in.required_string("file");
  if (file.empty()) in.fail("file", "the file name is empty");
  const std::string path = scene_relative_path(context.file, file);
  // what is wrong in the file is reported at the scene's key, naming the file and its line
  try {
    read_file_shape_at(in, path, type, limits, flex);
  } catch (const InputError& e) {
    if (e.where().file != path) throw;
    const std::string line = e.where().line > 0 ? ", line " + std::to_string(e.where().line) : std::string();
    in.fail("file", type + " file '" + path + "'" + line + ": " + e.detail());
  }
}

namespace {

void read_file_shape_at(TableReader& in, const std::string& path, const std::string& type, const LimitsDef& limits,
                        FlexBodyDef& flex) {
  if (type == "dxf") {
    // outlines: the body's shape is the outer loops, its holes gain the inner ones
    DxfShapeOptions options;
    options.layer = in.string("layer", "");
    options.scale = read_scale(in);
    options.tolerance = in.number("tolerance", -1.0, Sign::kPositive, true);
    in.finish({"center", "width", "height", "threshold", "block"}, "a 'dxf' shape");
    const DxfOutline outline = read_dxf_shape(path, options);
    std::vector<ShapeDef> outers;
    for (const std::vector<Vec2>& loop : outline.material) {
      ShapeDef polygon;
      polygon.kind = ShapeDef::Kind::kPolygon;
      polygon.vertices = loop;
      outers.push_back(std::move(polygon));
    }
    if (outers.size() == 1) {
      flex.shape = outers.front();
    } else {
      flex.shape.kind = ShapeDef::Kind::kBoolean;
      flex.shape.combine = ShapeDef::Combine::kUnion;
      flex.shape.operands = std::move(outers);
    }
    for (const std::vector<Vec2>& loop : outline.holes) {
      ShapeDef hole;
      hole.kind = ShapeDef::Kind::kPolygon;
      hole.vertices = loop;
      flex.holes.push_back(std::move(hole));
    }
    flex.geometry_source = "dxf " + path;
    return;
  }

  ParticleCloud cloud;
  if (type == "points") {
    // the particles as the file lists them
    PointFileOptions options;
    options.scale = read_scale(in);
    options.block = in.integer("block", -1, 0);
    options.max_points = limits.max_particles;
    in.finish({"center", "width", "height", "threshold", "layer", "tolerance"}, "a 'points' shape");
    cloud = read_point_file(path, options);
  } else {
    // a picture stretched over a rectangle, sampled at the grid spacing
    ImageShapeOptions options;
    options.center = in.vec2("center", Vec2::Zero());
    options.width = in.required_number("width", Sign::kPositive, true);
    options.height = in.number("height", 0.0, Sign::kPositive, true);
    options.threshold = in.number("threshold", 0.5, Sign::kPositive);
    if (options.threshold > 1.0)
      in.fail("threshold", "must be in (0, 1] (a relative luminance), found " + format_number(options.threshold));
    options.dx = flex.grid_spacing;
    options.thickness = flex.thickness;
    options.max_particles = limits.max_particles;
    in.finish({"unit", "scale", "block", "layer", "tolerance"}, "an 'image' shape");
    cloud = read_image_shape(path, options);
  }
  remove_holes(cloud, flex.holes);
  if (cloud.size() == 0) in.fail("file", "every point of '" + path + "' lies in a hole");
  // refused here, naming the file's line: coincident points, volumes far from the grid cell's
  place_on_lattice(cloud, flex.grid_spacing, flex.thickness, path);
  flex.shape = bounding_box(cloud, flex.grid_spacing);
  flex.geometry_source = cloud.source;
  flex.particles = std::make_shared<const ParticleCloud>(std::move(cloud));
}

}  // namespace

}  // namespace periflex
