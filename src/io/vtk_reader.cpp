#include "io/vtk_reader.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "output/checkpoint_file.h"

namespace periflex {

namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError("cannot read '" + path + "'");
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// The value of attribute `name` in the tag text, or "" when it has none.
std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const size_t from = at + key.size(), to = tag.find('"', from);
  return to == std::string::npos ? "" : tag.substr(from, to - from);
}

// `count` values of a VTK type read from raw little-endian bytes, as doubles
bool convert(const std::string& type, const char* bytes, size_t size, std::vector<double>& out) {
  const auto take = [&](auto sample) {
    using T = decltype(sample);
    if (size % sizeof(T) != 0) return false;
    out.resize(size / sizeof(T));
    for (size_t i = 0; i < out.size(); ++i) {
      T v;
      std::memcpy(&v, bytes + i * sizeof(T), sizeof(T));
      out[i] = static_cast<double>(v);
    }
    return true;
  };
  if (type == "Float64") return take(double());
  if (type == "Float32") return take(float());
  if (type == "Int64") return take(int64_t());
  if (type == "Int32") return take(int32_t());
  if (type == "UInt8") return take(uint8_t());
  return false;
}

}  // namespace

const std::vector<double>& VtkArrays::get(const std::string& name, size_t count) const {
  const auto it = arrays.find(name);
  if (it == arrays.end()) throw CheckpointError("'" + path + "' has no array " + name);
  if (it->second.size() != count)
    throw CheckpointError("'" + path + "': array " + name + " holds " + std::to_string(it->second.size()) +
                          " values, expected " + std::to_string(count));
  return it->second;
}

VtkArrays read_vtk_arrays(const std::string& path) {
  const std::string text = read_all(path);
  VtkArrays out;
  out.path = path;
  if (text.find("<VTKFile") == std::string::npos || text.find("header_type=\"UInt64\"") == std::string::npos)
    throw CheckpointError("'" + path + "' is not a VTK file written by periflex");
  // the raw block starts after the '_' that follows <AppendedData encoding="raw">
  const size_t appended = text.find("<AppendedData encoding=\"raw\">");
  const size_t block = appended == std::string::npos ? std::string::npos : text.find('_', appended);
  const size_t header_end = appended == std::string::npos ? text.size() : appended;
  for (size_t at = text.find("<DataArray"); at < header_end; at = text.find("<DataArray", at + 1)) {
    const size_t close = text.find('>', at);
    if (close == std::string::npos) break;
    const std::string tag = text.substr(at, close - at);
    const std::string name = attribute(tag, "Name"), type = attribute(tag, "type"), format = attribute(tag, "format");
    std::vector<double> values;
    if (format == "ascii") {
      std::istringstream in(text.substr(close + 1, text.find('<', close) - close - 1));
      for (double v; in >> v;) values.push_back(v);
    } else if (format == "appended" && block != std::string::npos) {
      // a UInt64 byte count, then the bytes
      const size_t offset = std::strtoull(attribute(tag, "offset").c_str(), nullptr, 10);
      const size_t start = block + 1 + offset;
      uint64_t bytes = 0;
      if (start + sizeof bytes > text.size()) throw CheckpointError("'" + path + "' is cut short (array " + name + ")");
      std::memcpy(&bytes, text.data() + start, sizeof bytes);
      if (bytes > text.size() - start - sizeof bytes)
        throw CheckpointError("'" + path + "' is cut short (array " + name + ")");
      if (!convert(type, text.data() + start + sizeof bytes, bytes, values))
        throw CheckpointError("'" + path + "': array " + name + " of type '" + type + "' cannot be read");
    } else {
      throw CheckpointError("'" + path + "': array " + name + " is neither ascii nor raw appended data");
    }
    out.arrays[name] = std::move(values);
  }
  return out;
}

std::vector<VtkDataSet> read_vtk_collection(const std::string& path) {
  const std::string text = read_all(path);
  if (text.find("type=\"Collection\"") == std::string::npos)
    throw CheckpointError("'" + path + "' is not a VTK collection (.pvd)");
  std::vector<VtkDataSet> sets;
  for (size_t at = text.find("<DataSet"); at != std::string::npos; at = text.find("<DataSet", at + 1)) {
    const std::string tag = text.substr(at, text.find('>', at) - at);
    VtkDataSet d;
    const std::string time = attribute(tag, "timestep"), part = attribute(tag, "part");
    d.file = attribute(tag, "file");
    char* end = nullptr;
    d.time = std::strtod(time.c_str(), &end);
    if (time.empty() || *end != '\0' || d.file.empty() || d.file.find('/') != std::string::npos)
      throw CheckpointError("'" + path + "' lists a data set that is not one periflex writes: " + tag + ">");
    d.part = part == "1" ? 1 : 0;
    sets.push_back(d);
  }
  if (sets.empty()) throw CheckpointError("'" + path + "' lists no data set");
  return sets;
}

}  // namespace periflex
