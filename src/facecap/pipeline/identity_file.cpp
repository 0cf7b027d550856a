#include "facecap/pipeline/identity_file.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "facecap/core/error.hpp"

namespace facecap {

Eigen::VectorXd read_identity_weights(const std::filesystem::path& path) {
  const std::string what = "cannot read an identity from " + path.string() + ": ";
  std::ifstream in(path);
  if (!in) throw Error(what + "no such file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    throw Error(what + "not JSON");
  }
  if (!j.is_object() || !j.contains("identity_weights") || !j["identity_weights"].is_array() ||
      j["identity_weights"].empty())
    throw Error(what + "no \"identity_weights\" (write one with facecap track)");
  const nlohmann::json& w = j["identity_weights"];
  Eigen::VectorXd weights(static_cast<Eigen::Index>(w.size()));
  for (size_t i = 0; i < w.size(); ++i) {
    if (!w[i].is_number() || !std::isfinite(w[i].get<double>()))
      throw Error(what + "identity weight " + std::to_string(i) + " is not a finite number");
    weights[static_cast<Eigen::Index>(i)] = w[i].get<double>();
  }
  return weights;
}

}  // namespace facecap
