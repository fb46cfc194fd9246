// Writing a file so that a full disk (or any failed write) is an error, not
// a silently short file: every write and the close are checked.
#pragma once

#include <filesystem>
#include <string_view>

namespace touchcloud {

// Creates or truncates `file` and writes `bytes`; RunError naming the file
// and the system's reason (e.g. "No space left on device") on any failure.
void write_file(const std::filesystem::path& file, std::string_view bytes);

// A write past the process's file-size limit (ulimit -f) raises SIGXFSZ,
// whose default action ends the process without a word and leaves the
// partial file. With the signal ignored the write fails with EFBIG ("File
// too large"), an error like a full disk. A program calls this once in
// main(); Python ignores the signal itself.
void ignore_file_size_signal();

}  // namespace touchcloud
