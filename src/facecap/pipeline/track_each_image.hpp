#pragma once
// `facecap track FOLDER -o DIR --each-image`: every image of a folder fitted
// on its own, as `track IMAGE` fits a photo (its own identity, its focal
// length from one view and a prior, any image size), where a plain folder
// input is one camera's frames with one face. For a set of portraits of
// different people (a dataset, a casting call): each image's files go to
// DIR/<its name without extension>/ as `track IMAGE -o` writes them
// (frames.csv, frames.jsonl, identity.json, and the meshes, glTF ... asked
// for), and one table holds them all:
//   DIR/images.csv    a row per image, in name order: its file name, status,
//                     pose, focal, landmark error, the 53 weights, gaze (the
//                     columns of frames.csv, without frame, time and shot),
//                     then its 50 identity weights id_0 ... id_49
//   DIR/images.jsonl  the same: the image's frames.jsonl row with "image",
//                     "folder", "size" and, where a face was fitted,
//                     "identity_weights"
// An image with no face is a row with status "lost"; one that cannot be
// decoded, status "error" (with the reason in images.jsonl); the others go
// on. Two images with one name but their extension get folders
// <name>_<extension>. Ctrl-C stops the whole run, and the folders it made
// are removed, as any interrupted run leaves nothing.
#include <filesystem>
#include <string>
#include <vector>

#include "facecap/pipeline/track_job.hpp"

namespace facecap {

struct EachImageSummary {
  int images = 0;
  int with_face = 0;                          // fitted (status tracked or redetected)
  int unreadable = 0;                         // status "error"
  std::string first_error;                    // the first unreadable image's reason
  std::vector<std::filesystem::path> tables;  // images.csv, images.jsonl
};

// Throws facecap::Error, before writing anything, where `folder` is no
// folder of images or the output folder cannot be written.
EachImageSummary run_track_each_image(const FaceModel& model, const std::filesystem::path& folder,
                                      const std::filesystem::path& output_dir, const TrackOptions& options);

}  // namespace facecap
