// The files of a recorded image sequence, in the order a reader walks them:
// a '{iteration}' pattern ("press_{iteration}.png": frames 0, 1, 2, ...
// without leading zeros, as RunContext::with_iteration numbers them) or a
// glob in the file name ("frames/*.png", in natural order: frame_2 before
// frame_10). Listed once before a run, so that `validate` finds a sequence
// that matches nothing or lacks a frame.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace touchcloud::io {

enum class SequenceKind { File, Numbered, Glob };

// What a path names: a '{iteration}' pattern, a glob ('*', '?' or '[' in the
// file name, when no file has that very name), or one file.
SequenceKind sequence_kind(const std::string& path);

// The sequence's files. InputError, naming the path, when nothing matches,
// when a numbered sequence does not start at frame 0 or lacks a frame
// between its first and its last ("frame 4 is missing"), or when the
// pattern or glob is in a folder name rather than the file name.
std::vector<std::filesystem::path> list_image_sequence(const std::string& path);

}  // namespace touchcloud::io
