// FFmpeg's own messages caught instead of printed. OpenCV's FFmpeg backend
// leaves FFmpeg's log on the terminal at error level: a damaged video's
// demuxer and decoder speak there ("moov atom not found", "ac-tex damaged
// at 17 1"), and the decoder hides the damage in the frame it returns. The
// capture turns what its open and its reads caught into the InputError of
// the file or the frame.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace touchcloud::camera {

// Installs the catcher once, unless OPENCV_FFMPEG_DEBUG or
// OPENCV_FFMPEG_LOGLEVEL ask OpenCV to show FFmpeg's log itself.
void catch_ffmpeg_messages();

// What FFmpeg said at error level since the last call, oldest first (the
// first 8). FFmpeg decodes on threads of its own (frame threads, whose
// contexts are private copies), so a message cannot be traced to its file:
// a second video read at the same time can see the other's messages.
std::vector<std::string> caught_ffmpeg_messages();

// A video file registered as being read while the token lives, so that a
// caught message names every file it may concern.
std::shared_ptr<const std::string> reading_video(const std::string& file);

// The files registered, other than `self`'s, in the order they were.
std::vector<std::string> videos_read_besides(const std::shared_ptr<const std::string>& self);

// The messages as one quoted phrase: "FFmpeg says 'a'; 'b'", and the files
// read at the time besides `reading`'s (registered by reading_video), when
// there are any.
std::string ffmpeg_says(const std::vector<std::string>& messages,
                        const std::shared_ptr<const std::string>& reading = nullptr);

}  // namespace touchcloud::camera
