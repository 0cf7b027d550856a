#pragma once
// The per-frame files a capture writes into a folder of their own
// (`--meshes`: meshes/frame_NNNNNN.obj; `--aligned-faces`:
// aligned/frame_NNNNNN.png), named by the frame's number in the input.
#include <filesystem>
#include <initializer_list>
#include <string>
#include <unordered_set>

namespace facecap {

// "frame_000042.png" for frame 42 and extension "png".
std::string frame_file_name(int frame, const char* extension);

// Removes the frame files (frame_*.<extension>, for any of `extensions`) in
// `dir` that are not named in `written`: an earlier run's frames past this
// run's end, or lost in it, would read as part of its sequence. Other files
// are left alone.
void remove_unwritten_frame_files(const std::filesystem::path& dir, std::initializer_list<const char*> extensions,
                                  const std::unordered_set<std::string>& written);

}  // namespace facecap
