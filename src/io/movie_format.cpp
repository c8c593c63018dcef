#include "io/movie_format.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>

#include "io/child_process.h"

namespace periflex {

const std::vector<MovieFormat>& movie_formats() {
  static const std::vector<MovieFormat> formats = {
      {".mp4", "mp4", "libx264", "H.264 in MP4", true},
      {".webm", "webm", "libvpx-vp9", "VP9 in WebM", false},
      {".mkv", "matroska", "libx264", "H.264 in Matroska", false},
      {".gif", "gif", "gif", "GIF with a palette made for each frame", false},
      {".avi", "avi", "mpeg4", "MPEG-4 part 2 in AVI", false},
  };
  return formats;
}

const MovieFormat* movie_format_of(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const MovieFormat& format : movie_formats())
    if (format.extension == extension) return &format;
  return nullptr;
}

std::set<std::string> parse_ffmpeg_listing(const std::string& listing) {
  std::set<std::string> names;
  std::istringstream lines(listing);
  std::string line;
  bool below_rule = false;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string flags, name;
    words >> flags;
    // the legend ends with a rule of dashes; the entries follow it
    if (!below_rule) {
      below_rule = !flags.empty() && flags.find_first_not_of('-') == std::string::npos;
      continue;
    }
    if (!(words >> name)) continue;
    // a muxer may carry several names ("mov,mp4,m4a")
    std::istringstream parts(name);
    for (std::string part; std::getline(parts, part, ',');)
      if (!part.empty()) names.insert(part);
  }
  return names;
}

const FfmpegAbilities& ffmpeg_abilities(const std::string& ffmpeg) {
  static std::mutex mutex;
  static std::map<std::string, FfmpegAbilities> known;
  std::lock_guard lock(mutex);
  auto found = known.find(ffmpeg);
  if (found != known.end()) return found->second;
  FfmpegAbilities abilities;
  ChildLimits limits;
  limits.timeout_seconds = 30.0;
  const ChildResult encoders = run_child({ffmpeg, "-hide_banner", "-encoders"}, limits);
  if (encoders.exit_code == 0) abilities.encoders = parse_ffmpeg_listing(encoders.output);
  const ChildResult muxers = run_child({ffmpeg, "-hide_banner", "-muxers"}, limits);
  if (muxers.exit_code == 0) abilities.muxers = parse_ffmpeg_listing(muxers.output);
  return known.emplace(ffmpeg, std::move(abilities)).first->second;
}

std::string writable_extensions(const FfmpegAbilities& abilities) {
  std::string out;
  for (const MovieFormat& format : movie_formats())
    if (abilities.can_write(format)) out += (out.empty() ? "" : ", ") + format.extension;
  return out.empty() ? "none" : out;
}

std::vector<std::string> movie_output_args(const MovieFormat& format, double fps) {
  // a keyframe every second: an MP4 fragment each, and seeking that is never far off
  char gop[32];
  std::snprintf(gop, sizeof gop, "%d", std::max(1, static_cast<int>(fps + 0.5)));
  // yuv420p halves the colour resolution, so the codecs that use it need even sizes
  const std::vector<std::string> even = {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p"};
  std::vector<std::string> args = {"-an"};
  const auto add = [&args](const std::vector<std::string>& more) { args.insert(args.end(), more.begin(), more.end()); };
  if (format.encoder == "libx264") {
    add(even);
    add({"-c:v", "libx264", "-preset", "veryfast", "-g", gop});
    if (format.fragmented) add({"-movflags", "frag_keyframe+empty_moov+default_base_moof"});
  } else if (format.encoder == "libvpx-vp9") {
    // constant quality (-b:v 0 -crf); the realtime settings keep encoding near the drawing's pace
    add(even);
    add({"-c:v", "libvpx-vp9", "-b:v", "0", "-crf", "32", "-deadline", "realtime", "-cpu-used", "8", "-row-mt", "1",
         "-g", gop});
  } else if (format.encoder == "gif") {
    // 256 colours a frame: a palette made from each frame (so memory stays one frame, not the
    // whole movie) and used for that frame alone
    add({"-vf", "split[a][b];[a]palettegen=stats_mode=single[p];[b][p]paletteuse=new=1", "-c:v", "gif"});
  } else {
    add(even);
    add({"-c:v", format.encoder, "-q:v", "3", "-g", gop});
  }
  add({"-f", format.muxer});
  return args;
}

long movie_file_frames(const std::string& ffmpeg, const std::string& path) {
  // framecrc prints one line per packet of the video stream, copied, not decoded
  ChildLimits limits;
  limits.timeout_seconds = 120.0;
  const ChildResult r =
      run_child({ffmpeg, "-hide_banner", "-v", "error", "-nostdin", "-i", path, "-map", "0:v:0", "-c", "copy", "-f",
                 "framecrc", "-"},
                limits);
  if (r.exit_code != 0) return -1;
  long frames = 0;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0]))) ++frames;
  return frames;
}

}  // namespace periflex
