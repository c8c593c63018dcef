#include "io/frame_writer.h"

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "io/child_process.h"
#include "io/movie_format.h"
#include "io/mp4_fragments.h"

namespace periflex {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------
// PNG sequence

PngSequenceWriter::PngSequenceWriter(std::string dir) : dir_(std::move(dir)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_))
    throw std::runtime_error("cannot create frames folder " + dir_ + ": " + ec.message());
}

std::string PngSequenceWriter::frame_path(long i) const {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06ld.png", i);
  return (fs::path(dir_) / name).string();
}

void PngSequenceWriter::write_numbered(long i, const RgbaImage& frame) const {
  write_png(frame_path(i), frame);
}

void PngSequenceWriter::write(const RgbaImage& frame) {
  write_numbered(count_, frame);
  ++count_;
}

// ---------------------------------------------------------------------------
// ffmpeg discovery

std::string find_ffmpeg() { return find_program("ffmpeg"); }

void check_movie_output(const std::string& movie_path, const std::string& option, const std::string& ffmpeg) {
  // a flag is named as on the command line ("--movie"), a window's field by its name
  SourceLocation where;
  where.key = option;
  if (option.rfind("--", 0) == 0) where.file = "command line";
  const std::string exe = ffmpeg.empty() ? find_ffmpeg() : ffmpeg;
  if (exe.empty())
    throw InputError(where, "writing " + movie_path + " needs ffmpeg, which is not on PATH; install it "
                     "(apt-get install ffmpeg) or write PNG frames instead");
  // the format by its extension, and whether this ffmpeg has its encoder and container
  const FfmpegAbilities& abilities = ffmpeg_abilities(exe);
  const MovieFormat* format = movie_format_of(movie_path);
  if (!format) {
    std::string known;
    for (const MovieFormat& f : movie_formats()) known += (known.empty() ? "" : ", ") + f.extension;
    throw InputError(where, "'" + movie_path + "' does not end in a movie extension periflex writes (" + known +
                                "); this ffmpeg (" + exe + ") can write " + writable_extensions(abilities));
  }
  if (!abilities.can_write(*format)) {
    const std::string missing = !abilities.encoders.count(format->encoder)
                                    ? "the encoder " + format->encoder
                                    : "the container " + format->muxer;
    throw InputError(where, "a " + format->extension + " movie (" + format->description + ") needs " + missing +
                                ", which this ffmpeg (" + exe + ") does not have; it can write " +
                                writable_extensions(abilities));
  }
  fs::path parent = fs::path(movie_path).parent_path();
  if (parent.empty()) parent = ".";
  std::error_code ec;
  if (!fs::is_directory(parent, ec))
    throw InputError(where, "the folder of " + movie_path + " does not exist");
  if (::access(parent.c_str(), W_OK) != 0)
    throw InputError(where, "the folder of " + movie_path + " is not writable");
}

// ---------------------------------------------------------------------------
// Movies through ffmpeg

namespace {

// A hidden name beside the movie, unique to this process: .NAME.PID.part
std::string temporary_path(const std::string& path) {
  const fs::path p(path);
  // appended piece by piece: GCC 12 warns (-Wrestrict) about "." + std::string here
  std::string name(1, '.');
  name += p.filename().string();
  name += '.';
  name += std::to_string(::getpid());
  name += ".part";
  return (p.parent_path() / name).string();
}

}  // namespace

MovieWriter::MovieWriter(std::string path, int width, int height, double fps, const std::string& ffmpeg)
    : path_(std::move(path)), width_(width), height_(height) {
  ffmpeg_ = ffmpeg.empty() ? find_ffmpeg() : ffmpeg;
  check_movie_output(path_, "movie", ffmpeg_);
  if (width <= 0 || height <= 0 || !(fps > 0.0))
    throw std::runtime_error("movie " + path_ + ": invalid size or frame rate");
  const MovieFormat& format = *movie_format_of(path_);
  fragmented_ = format.fragmented;
  writing_path_ = fragmented_ ? path_ : temporary_path(path_);

  // ffmpeg's messages go to a log file so that a failure can be explained
  char log_template[] = "/tmp/periflex-ffmpeg-XXXXXX";
  const int log_fd = ::mkstemp(log_template);
  if (log_fd < 0) throw std::runtime_error(std::string("cannot create ffmpeg log: ") + std::strerror(errno));
  log_path_ = log_template;

  // a socket rather than a pipe: send() with MSG_NOSIGNAL reports a dead ffmpeg as EPIPE
  // instead of killing the whole program with SIGPIPE
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
    ::close(log_fd);
    throw std::runtime_error(std::string("cannot create ffmpeg input socket: ") + std::strerror(errno));
  }

  char size[64], rate[32];
  std::snprintf(size, sizeof size, "%dx%d", width, height);
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  std::vector<std::string> args = {ffmpeg_, "-hide_banner", "-loglevel", "error", "-y",
                                   "-f", "rawvideo", "-pix_fmt", "rgba", "-s", size, "-r", rate, "-i", "-"};
  const std::vector<std::string> output = movie_output_args(format, fps);
  args.insert(args.end(), output.begin(), output.end());
  args.push_back(writing_path_);
  // input "-" also tells ffmpeg not to read keyboard commands from it; a process group of its
  // own (start_child): Ctrl-C at the terminal stops periflex, which then closes the movie
  // cleanly, instead of reaching ffmpeg too and cutting the movie short
  std::string error;
  pid_ = start_child(args, {sv[1], log_fd}, error);
  ::close(sv[1]);
  ::close(log_fd);
  if (pid_ < 0) {
    ::close(sv[0]);
    std::remove(log_path_.c_str());
    throw std::runtime_error(error);
  }
  fd_ = sv[0];
}

MovieWriter::~MovieWriter() {
  try {
    close();
  } catch (...) {
    // a destructor cannot report; callers who care call close() themselves
  }
}

std::string MovieWriter::fail_message(const std::string& what) const {
  // the last few lines of ffmpeg's log say why it stopped
  std::ifstream log(log_path_);
  std::string line, tail;
  std::vector<std::string> lines;
  while (std::getline(log, line)) lines.push_back(line);
  for (size_t i = lines.size() > 5 ? lines.size() - 5 : 0; i < lines.size(); ++i) tail += "\n  " + lines[i];
  return "movie " + path_ + ": " + what + (tail.empty() ? "" : "; ffmpeg says:" + tail);
}

void MovieWriter::write(const RgbaImage& frame) {
  if (fd_ < 0) throw std::runtime_error("movie " + path_ + ": write after close");
  if (frame.width != width_ || frame.height != height_)
    throw std::runtime_error("movie " + path_ + ": frame is " + std::to_string(frame.width) + "x" +
                             std::to_string(frame.height) + ", expected " + std::to_string(width_) + "x" +
                             std::to_string(height_));
  // send the whole frame, resuming after partial writes
  const uint8_t* data = frame.pixels.data();
  size_t left = frame.pixels.size();
  while (left > 0) {
    const ssize_t n = ::send(fd_, data, left, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      throw std::runtime_error(fail_message(std::string("ffmpeg stopped reading frames (") + std::strerror(e) + ")"));
    }
    data += n;
    left -= static_cast<size_t>(n);
  }
  ++count_;
}

void MovieWriter::close() {
  if (pid_ < 0) return;
  // end of input tells ffmpeg to finish the file
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  int status = 0;
  pid_t r;
  do {
    r = ::waitpid(pid_, &status, 0);
  } while (r < 0 && errno == EINTR);
  pid_ = -1;
  const bool ok = r > 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  std::string failure;
  if (!ok)
    failure = fail_message(WIFSIGNALED(status) ? "ffmpeg was killed by signal " + std::to_string(WTERMSIG(status))
                                               : "ffmpeg exited with status " + std::to_string(WEXITSTATUS(status)));
  std::remove(log_path_.c_str());
  if (!failure.empty()) {
    // what the file holds decides what is kept: a fragmented MP4's whole fragments play
    if (fragmented_) {
      count_ = read_mp4_fragments(path_).samples;
      if (count_ == 0) std::remove(path_.c_str());
    } else {
      count_ = 0;
      std::remove(writing_path_.c_str());
    }
    throw std::runtime_error(failure);
  }
  keep_or_remove();
}

void MovieWriter::keep_or_remove() {
  // ffmpeg exits with success even when the disk refused part of the file: read it back
  const long sent = count_;
  if (fragmented_) {
    const Mp4Fragments movie = read_mp4_fragments(path_);
    if (movie.whole && movie.samples == sent) return;
    count_ = movie.samples;
    if (count_ == 0) std::remove(path_.c_str());
    throw std::runtime_error("movie " + path_ + ": the file holds " + std::to_string(movie.samples) + " of the " +
                             std::to_string(sent) + " frames sent to ffmpeg" +
                             (movie.whole ? "" : ", its last part cut short") + " (disk full?)" +
                             (count_ == 0 ? "; it was removed" : ""));
  }
  const long held = movie_file_frames(ffmpeg_, writing_path_);
  std::error_code ec;
  if (held == sent) fs::rename(writing_path_, path_, ec);
  if (held == sent && !ec) return;
  count_ = 0;
  std::remove(writing_path_.c_str());
  if (held != sent)
    throw std::runtime_error("movie " + path_ + ": the file ffmpeg wrote holds " +
                             (held < 0 ? std::string("no readable frames") : std::to_string(held) + " frames") +
                             " of the " + std::to_string(sent) + " sent (disk full?); nothing was kept");
  throw std::runtime_error("movie " + path_ + ": cannot rename " + writing_path_ + " to it: " + ec.message());
}

}  // namespace periflex
