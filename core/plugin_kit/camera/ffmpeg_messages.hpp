// FFmpeg's own messages caught instead of printed. OpenCV's FFmpeg backend
// leaves FFmpeg's log on the terminal at error level: a damaged video's
// demuxer and decoder speak there ("moov atom not found", "ac-tex damaged
// at 17 1"), and the decoder hides the damage in the frame it returns. The
// capture turns what its open and its reads caught into the InputError of
// the file or the frame.
#pragma once

#include <string>
#include <vector>

namespace touchcloud::camera {

// Installs the catcher once, unless OPENCV_FFMPEG_DEBUG or
// OPENCV_FFMPEG_LOGLEVEL ask OpenCV to show FFmpeg's log itself.
void catch_ffmpeg_messages();

// What FFmpeg said at error level since the last call, oldest first (the
// first 8). FFmpeg decodes on threads of its own: a second video read at
// the same time can see the other's messages.
std::vector<std::string> caught_ffmpeg_messages();

// The messages as one quoted phrase: "FFmpeg says 'a'; 'b'".
std::string ffmpeg_says(const std::vector<std::string>& messages);

}  // namespace touchcloud::camera
