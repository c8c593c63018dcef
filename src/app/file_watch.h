// Notices when a file changes on disk, for the window's hot reload of the scene: its
// modification time and size are compared with those seen last, at most every `interval`
// seconds, so polling it once a frame costs a stat call now and then. No GL; internal to src/app/.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace periflex {

class FileWatch {
 public:
  explicit FileWatch(double interval = 0.3) : interval_(interval) {}
  // Watches `path` from now on (its present state is the one seen); an empty path watches nothing.
  void watch(const std::string& path, double now);
  const std::string& path() const { return path_; }
  // True once for every change seen since the last call (checked when `interval` has passed
  // since the last check; `now` in seconds of any steady clock). A file that disappears is no
  // change; one that comes back different is.
  bool changed(double now);

 private:
  struct Stamp {
    bool exists = false;
    std::filesystem::file_time_type time{};
    std::uintmax_t size = 0;
    bool operator==(const Stamp& o) const { return exists == o.exists && time == o.time && size == o.size; }
  };
  Stamp stamp() const;

  double interval_;
  std::string path_;
  Stamp seen_;
  double last_check_ = -1e300;
};

}  // namespace periflex
