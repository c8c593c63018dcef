// The movie formats periflex writes through ffmpeg, chosen by the file's extension, and what the
// installed ffmpeg can write of them. A movie is checked against both before anything is
// simulated, so a format ffmpeg cannot write is refused up front instead of after the run.
#pragma once

#include <set>
#include <string>
#include <vector>

namespace periflex {

struct MovieFormat {
  std::string extension;    // ".mp4", lower case
  std::string muxer;        // ffmpeg's container name (-f)
  std::string encoder;      // ffmpeg's video encoder (-c:v)
  std::string description;  // what the user reads: "H.264 in MP4"
  // Written in place under its own name as a fragmented MP4, which a run killed part-way leaves
  // playable up to its last whole fragment; the other formats are written under a temporary name
  // and renamed once ffmpeg has closed them cleanly.
  bool fragmented = false;
};

// Every format, in the order the messages list them: .mp4, .webm, .mkv, .gif, .avi.
const std::vector<MovieFormat>& movie_formats();

// The format of `path` by its extension, in any case (".GIF" is ".gif"), or nullptr.
const MovieFormat* movie_format_of(const std::string& path);

// The encoders and muxers an ffmpeg executable lists (-encoders, -muxers), asked once per
// executable and remembered. Empty when it could not be run.
struct FfmpegAbilities {
  std::set<std::string> encoders, muxers;
  bool can_write(const MovieFormat& format) const {
    return encoders.count(format.encoder) && muxers.count(format.muxer);
  }
};
const FfmpegAbilities& ffmpeg_abilities(const std::string& ffmpeg);

// "-encoders" / "-muxers" listings to names (the lines below the "------" rule; the name is the
// second word of each). Exposed for tests.
std::set<std::string> parse_ffmpeg_listing(const std::string& listing);

// The extensions (".mp4, .webm, ...") of the formats `abilities` can write.
std::string writable_extensions(const FfmpegAbilities& abilities);

// ffmpeg's output arguments for `format` at `fps`, up to (not including) the output path: the
// codec, its pixel format and speed, the GIF palette, the MP4 fragments.
std::vector<std::string> movie_output_args(const MovieFormat& format, double fps);

// The video frames a finished movie file holds, counted by ffmpeg reading its packets back
// (no decoding); -1 when ffmpeg could not read the file.
long movie_file_frames(const std::string& ffmpeg, const std::string& path);

}  // namespace periflex
