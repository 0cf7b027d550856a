#pragma once
// `facecap track --all-faces`: every face the input shows, each captured into
// a folder of its own (DIR/face_<k>, k in the order found, left to right
// among faces found together) from the frame it is first found in, as
// `track --start T --face X,Y` at that frame and face would capture it, and
// DIR/faces.json listing them, with DIR/faces.png showing each face where it
// was found, labelled with its folder and that frame. One decoding pass for all (face_roster.hpp),
// so a camera works too. Folders face_<k> of an earlier run with more faces
// are removed.
#include <filesystem>
#include <string>
#include <vector>

#include "facecap/pipeline/face_roster.hpp"
#include "facecap/pipeline/track_job.hpp"

namespace facecap {

struct EachFaceSummary {
  std::vector<FoundFace> faces;    // in the order found
  std::vector<TrackSummary> runs;  // one per face, in that order
  AllFacesSummary capture;         // the shared pass
};

// Throws facecap::Error where no face is found in the whole input; nothing
// is written then.
EachFaceSummary run_track_each_face(const FaceModel& model, const std::string& input,
                                    const std::filesystem::path& output_dir, const TrackOptions& options,
                                    const AllFacesOptions& all = {});

// Each face's thumbnail in a row (eight to a row), labelled "face_<k> @<frame>".
cv::Mat faces_contact_sheet(const std::vector<FoundFace>& faces);

// The folder of face `k` (DIR/face_<k>).
std::filesystem::path face_folder(const std::filesystem::path& output_dir, int k);

}  // namespace facecap
