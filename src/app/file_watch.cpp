#include "app/file_watch.h"

namespace periflex {

FileWatch::Stamp FileWatch::stamp() const {
  Stamp s;
  std::error_code ec;
  s.time = std::filesystem::last_write_time(path_, ec);
  if (ec) return s;
  s.size = std::filesystem::file_size(path_, ec);
  s.exists = !ec;
  return s;
}

void FileWatch::watch(const std::string& path, double now) {
  path_ = path;
  seen_ = path_.empty() ? Stamp{} : stamp();
  last_check_ = now;
}

bool FileWatch::changed(double now) {
  if (path_.empty() || now - last_check_ < interval_) return false;
  last_check_ = now;
  const Stamp current = stamp();
  // gone (an editor replacing it): wait for it to come back
  if (!current.exists) return false;
  if (current == seen_) return false;
  seen_ = current;
  return true;
}

}  // namespace periflex
