// What a fragmented MP4 file (the movies ffmpeg writes for periflex: an empty moov, then a moof
// and an mdat per fragment) really holds: ffmpeg exits with success even when the disk refused
// part of the file, so the movie's writer reads the file back to see whether every frame is in it.
#pragma once

#include <string>

namespace periflex {

struct Mp4Fragments {
  long samples = 0;    // frames in the fragments whose moof and mdat are both whole
  bool whole = false;  // the boxes end exactly where the file does
};

// Walks the top-level boxes of the file at `path`, counting the samples of each fragment's track
// runs. A missing or unreadable file holds nothing (whole = false).
Mp4Fragments read_mp4_fragments(const std::string& path);

}  // namespace periflex
