// Writers that turn a stream of RGBA frames into files: a numbered PNG sequence or a movie
// (io/movie_format.h: MP4, WebM, Matroska, GIF, AVI) encoded by an ffmpeg child process. They need no GL, so the GUI can record from its window and
// the off-screen recorder from its framebuffer with the same code.
#pragma once

#include <string>
#include <sys/types.h>

#include "io/image.h"

namespace periflex {

// Common interface: write frames in order, then close (which reports late failures).
class FrameWriter {
 public:
  virtual ~FrameWriter() = default;
  // Appends one frame. Throws std::runtime_error with a clear reason on failure.
  virtual void write(const RgbaImage& frame) = 0;
  // Finishes the output; throws when it could not be completed. Safe to call twice.
  virtual void close() = 0;
  // Frames accepted so far.
  virtual long frames_written() const = 0;
};

// DIR/frame_000000.png, DIR/frame_000001.png, ... Each file appears complete or not at all
// (written under a temporary name, then renamed). The folder is created when missing.
class PngSequenceWriter : public FrameWriter {
 public:
  explicit PngSequenceWriter(std::string dir);
  void write(const RgbaImage& frame) override;
  void close() override {}
  long frames_written() const override { return count_; }
  // Path of frame number i.
  std::string frame_path(long i) const;
  // Writes frame number i (any order; several threads may write different numbers at once).
  void write_numbered(long i, const RgbaImage& frame) const;

 private:
  std::string dir_;
  long count_ = 0;
};

// Absolute path of the ffmpeg executable on PATH, or an empty string when there is none.
std::string find_ffmpeg();

// Checks before any simulation starts that a movie can be written to `movie_path`: ffmpeg exists,
// the extension names a format of io/movie_format.h that this ffmpeg can write, and the folder is
// writable. Throws periflex::InputError (exit code 2) keyed by `option` (e.g. "--movie") with
// what it can write, or the remedy, in the message.
void check_movie_output(const std::string& movie_path, const std::string& option = "--movie",
                        const std::string& ffmpeg = "");

// A movie written by ffmpeg reading raw RGBA frames from a socket on its standard input, in the
// format its extension names (io/movie_format.h). An MP4 is written in place as a fragmented MP4
// (one fragment per keyframe, one keyframe per second), so a run killed part-way leaves a file
// that plays up to its last complete second. The other formats are written under a temporary
// name beside the movie and renamed to it only once ffmpeg has closed the file cleanly and it
// holds every frame sent: a failed movie leaves no broken file under the name asked for (nor
// does an MP4 that holds no whole frame).
class MovieWriter : public FrameWriter {
 public:
  // Starts ffmpeg. Throws periflex::InputError when ffmpeg is missing or the extension names no
  // format it can write, std::runtime_error when it cannot be started.
  MovieWriter(std::string path, int width, int height, double fps, const std::string& ffmpeg = "");
  ~MovieWriter() override;
  // Throws std::runtime_error (with the end of ffmpeg's log) when ffmpeg has died or the frame
  // size differs from the one given at construction.
  void write(const RgbaImage& frame) override;
  // Closes ffmpeg's input and waits for it; throws when it exits with an error, or when the
  // file does not hold every frame sent (ffmpeg ignores a full disk).
  void close() override;
  // Frames sent to ffmpeg; after close() found the file short, the frames the file holds under
  // the name asked for (0 when nothing was kept).
  long frames_written() const override { return count_; }
  // Where ffmpeg writes until the movie is complete: the path itself for an MP4.
  const std::string& writing_path() const { return writing_path_; }

 private:
  std::string fail_message(const std::string& what) const;
  // Throws when the closed file is not the whole movie; renames it into place when it is.
  void keep_or_remove();
  std::string path_, writing_path_, log_path_, ffmpeg_;
  bool fragmented_ = false;
  int width_, height_;
  int fd_ = -1;
  pid_t pid_ = -1;
  long count_ = 0;
};

}  // namespace periflex
