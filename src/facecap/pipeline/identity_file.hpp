#pragma once
// Reading back the identity a capture wrote (`track`'s identity.json), so
// that later captures of the same person can hold it (`--identity FILE`,
// CoarseFitOptions::known_identity): takes of one actor then share one face.
#include <Eigen/Core>
#include <filesystem>

namespace facecap {

// The top-level "identity_weights" of an identity.json (the first shot's
// where the capture cut). Throws facecap::Error naming the file and what is
// wrong: missing, not JSON, no weights, a value that is not a finite number.
Eigen::VectorXd read_identity_weights(const std::filesystem::path& path);

}  // namespace facecap
