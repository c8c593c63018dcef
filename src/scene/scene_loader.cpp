#include "scene/scene_loader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <toml++/toml.h>

#include "scene/integrator_catalogue.h"
#include "scene/scene_overrides.h"
#include "scene/scene_reader.h"
#include "scene/toml_reader.h"

namespace periflex {

const std::vector<std::string>& scene_integrator_names() {
  // every integrator the solver has, and no other name: a scene that loads also runs
  static const std::vector<std::string> names = integrator_names();
  return names;
}

namespace {

// The size cap of scene files: kMaxSceneBytes, or PERIFLEX_MAX_SCENE_BYTES when set to a number.
long scene_size_cap() {
  const char* text = std::getenv("PERIFLEX_MAX_SCENE_BYTES");
  if (text == nullptr || *text == '\0') return kMaxSceneBytes;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  return *end == '\0' && value >= 1 && value <= 1e12 ? static_cast<long>(value) : kMaxSceneBytes;
}

// Reads a regular file of at most `cap` bytes. FIFOs, devices and folders are refused without
// reading (opening does not wait for a FIFO's writer), and no more than cap + 1 bytes are read
// whatever the file claims.
std::string read_bounded(const std::string& path, long cap) {
  SourceLocation where;
  where.file = path;
  if (path.empty()) throw InputError({"command line", 0, 0, "scene"}, "the scene file name is empty");
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) throw InputError(where, std::string("cannot open the scene file: ") + std::strerror(errno));
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw InputError(where, std::string("cannot read the scene file: ") + std::strerror(errno));
  if (S_ISDIR(info.st_mode)) throw InputError(where, "is a directory, not a scene file");
  if (!S_ISREG(info.st_mode))
    throw InputError(where, std::string("is not a regular file (") +
                     (S_ISFIFO(info.st_mode) ? "a FIFO" : S_ISCHR(info.st_mode) ? "a character device"
                      : S_ISBLK(info.st_mode) ? "a block device" : S_ISSOCK(info.st_mode) ? "a socket" : "a special file") +
                     "); scene files are read from regular files only");
  const auto too_big = [&](long long size) {
    return InputError(where, "the scene file has " + std::to_string(size) + (size > cap ? "" : "+") +
                      " bytes, more than the limit of " + std::to_string(cap) +
                      " (set PERIFLEX_MAX_SCENE_BYTES to raise it)");
  };
  if (info.st_size > cap) throw too_big(static_cast<long long>(info.st_size));
  // blocking reads from here on; never more than cap + 1 bytes
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  std::string text;
  text.reserve(static_cast<size_t>(info.st_size) + 1);
  char chunk[1 << 16];
  size_t used = 0;
  while (used <= static_cast<size_t>(cap)) {
    const size_t want = std::min(sizeof chunk, static_cast<size_t>(cap) + 1 - used);
    const ssize_t n = ::read(fd, chunk, want);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(where, std::string("cannot read the scene file: ") + std::strerror(errno));
    if (n == 0) break;
    text.append(chunk, static_cast<size_t>(n));
    used += static_cast<size_t>(n);
  }
  if (used > static_cast<size_t>(cap)) throw too_big(static_cast<long long>(used));
  return text;
}

}  // namespace

SceneDef load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  // a bounded read of a regular file; a missing or unreadable file is bad input too
  const std::string text = read_bounded(path, scene_size_cap());
  return parse_scene(text, path, overrides);
}

SceneDef parse_scene(std::string_view toml_text, const std::string& display_path,
                     const std::vector<std::string>& overrides) {
  ReadContext context;
  context.file = display_path;

  // TOML syntax first: toml++ reports the line and column of the first error
  toml::table root = parse_toml_located(toml_text, display_path);

  // overrides change the tree, so their values are checked like the file's
  apply_overrides(root, overrides, context);

  SceneDef scene = read_scene_tables(root, context, std::filesystem::path(display_path).stem().string());
  scene.path = display_path;
  return scene;
}

}  // namespace periflex
