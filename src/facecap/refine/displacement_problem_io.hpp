#pragma once
// One displacement problem on disk: the hierarchy level's topology, the base
// surface, albedo, lighting, samples, the regularisers' targets and the
// starting displacements. `facecap eval refine --save-problems DIR` writes the
// problems of real footage; `facecap bench displacement DIR` solves them
// again on each device, without the face model or the footage: the
// CPU/CUDA comparison and the solver's timing on any machine.
#include <filesystem>
#include <memory>
#include <vector>

#include "facecap/refine/displacement_solver.hpp"

namespace facecap {

struct SavedDisplacementProblem {
  int frame = 0;
  int level_index = 0;
  MeshLevel level;
  VertexSamples samples;
  DisplacementProblem problem;  // its level and samples point into this object
  Eigen::VectorXf start;        // d before the solve
};

// Writes atomically (facecap::Error when the path cannot be written).
void save_displacement_problem(const std::filesystem::path& path, const DisplacementProblem& problem,
                               const Eigen::VectorXf& start, int frame, int level_index);
// Throws facecap::Error naming the file when it is missing, truncated or not a problem file.
std::unique_ptr<SavedDisplacementProblem> load_displacement_problem(const std::filesystem::path& path);
// Every .fcdp file in `dir`, in frame then level order. Throws facecap::Error
// when the folder is missing, holds none, or one of them is unreadable.
std::vector<std::unique_ptr<SavedDisplacementProblem>> load_displacement_problems(const std::filesystem::path& dir);

}  // namespace facecap
