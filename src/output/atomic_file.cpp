#include "output/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace periflex {

void write_file_atomically(const std::string& path, std::string_view content) {
  const std::string temporary = path + ".tmp";
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (!file) throw std::runtime_error("cannot write " + temporary);
  const size_t written = std::fwrite(content.data(), 1, content.size(), file);
  const bool flushed = std::fflush(file) == 0;
  std::fclose(file);
  if (written != content.size() || !flushed) {
    std::remove(temporary.c_str());
    throw std::runtime_error("could not write all of " + path + " (disk full?)");
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) throw std::runtime_error("cannot rename " + temporary + " to " + path + ": " + error.message());
}

bool overwrite_in_place(const std::string& path, std::string_view content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat status {};
  // st_blocks counts 512-byte units whatever the file system's block size
  bool done = ::fstat(fd, &status) == 0 && static_cast<size_t>(status.st_blocks) * 512 >= content.size();
  for (size_t at = 0; done && at < content.size();) {
    const ssize_t n = ::pwrite(fd, content.data() + at, content.size() - at, static_cast<off_t>(at));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) done = false;
    else at += static_cast<size_t>(n);
  }
  if (done) done = ::ftruncate(fd, static_cast<off_t>(content.size())) == 0;
  ::close(fd);
  return done;
}

void ensure_directory(const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw std::runtime_error("cannot create directory " + dir + ": " + error.message());
}

}  // namespace periflex
