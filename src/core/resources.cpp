#include "core/resources.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace periflex {

namespace fs = std::filesystem;

namespace {

// a folder the program can draw from: it has the shaders (assets and scenes travel with them)
bool holds_resources(const fs::path& folder) {
  std::error_code ec;
  return !folder.empty() && fs::is_directory(folder / "shaders", ec);
}

// the running program's own path, through the link the kernel keeps for it; empty if unreadable
std::string own_program_path() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : self.string();
}

}  // namespace

std::string pick_resource_root(const std::string& program_path, const std::string& env_root,
                               const std::string& source_root) {
  // an installed program: PREFIX/bin/periflex beside PREFIX/share/periflex
  if (!program_path.empty()) {
    const fs::path installed = fs::path(program_path).parent_path().parent_path() / "share" / "periflex";
    if (holds_resources(installed)) return installed.string();
  }
  if (!env_root.empty() && holds_resources(env_root)) return env_root;
  if (holds_resources(source_root)) return source_root;
  // nothing found: a variable the user set is what they expect to be told about
  return env_root.empty() ? source_root : env_root;
}

std::string find_resource_root() {
  const char* env = std::getenv("PERIFLEX_ROOT");
  return pick_resource_root(own_program_path(), env ? env : "", PERIFLEX_SOURCE_ROOT);
}

}  // namespace periflex
