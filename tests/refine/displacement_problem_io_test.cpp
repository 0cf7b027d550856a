#include "facecap/refine/displacement_problem_io.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "bump_case.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"

namespace facecap {

using test::BumpCase;

// A saved problem solves to exactly what the original does.
TEST(DisplacementProblemIo, RoundTripSolvesTheSame) {
  const BumpCase c;
  DisplacementProblem problem = c.problem(true);
  problem.active.assign(c.base.cols(), true);
  problem.active[5] = false;
  const Eigen::VectorXf start = 0.2f * c.truth;
  const TempDir dir("facecap-problem-io");
  const auto path = dir.path() / "p.fcdp";
  save_displacement_problem(path, problem, start, 7, 1);
  const auto loaded = load_displacement_problem(path);
  EXPECT_EQ(loaded->frame, 7);
  EXPECT_EQ(loaded->level_index, 1);
  EXPECT_EQ(loaded->start, start);
  EXPECT_EQ(loaded->problem.active, problem.active);
  Eigen::VectorXf d_original = start, d_loaded = loaded->start;
  const DisplacementReport a = solve_displacements(problem, d_original);
  const DisplacementReport b = solve_displacements(loaded->problem, d_loaded);
  EXPECT_EQ(a.final_cost, b.final_cost);
  EXPECT_EQ(d_original, d_loaded);
}

// A truncated file, a file of something else and a missing one: one-line errors naming the file.
TEST(DisplacementProblemIo, BadFilesAreClearErrors) {
  const BumpCase c;
  const TempDir dir("facecap-problem-io");
  const auto path = dir.path() / "p.fcdp";
  save_displacement_problem(path, c.problem(), Eigen::VectorXf::Zero(c.base.cols()), 0, 0);
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  const auto message = [](const std::filesystem::path& p) {
    try {
      load_displacement_problem(p);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(path).find("truncated"), std::string::npos) << message(path);
  std::ofstream(dir.path() / "other.fcdp") << "not a problem at all, just some text";
  EXPECT_NE(message(dir.path() / "other.fcdp").find("not a facecap displacement problem"), std::string::npos);
  EXPECT_NE(message(dir.path() / "missing.fcdp").find("cannot open"), std::string::npos);
}

}  // namespace facecap
