#pragma once
// A progress bar on stderr for long jobs: done/total, frames per second and
// time left. Redraws in place on a terminal; on a pipe or log file it prints
// a line every few seconds instead, so CI logs stay readable.
#include <chrono>
#include <string>

namespace facecap {

class Progress {
 public:
  // total <= 0: unknown length. quiet: print nothing.
  Progress(std::string label, int total, bool quiet = false);
  ~Progress();
  void update(int done);
  void finish();

 private:
  void draw(int done, bool final_line);

  std::string label_;
  int total_;
  bool quiet_;
  bool tty_;
  bool finished_ = false;
  int last_done_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace facecap
