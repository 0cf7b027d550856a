#include "facecap/core/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace facecap {

Progress::Progress(std::string label, int total, bool quiet)
    : label_(std::move(label)),
      total_(total),
      quiet_(quiet),
      tty_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

Progress::~Progress() { finish(); }

void Progress::update(int done) {
  last_done_ = done;
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_draw_).count();
  if (since < (tty_ ? 0.1 : 5.0)) return;
  last_draw_ = now;
  draw(done, false);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (!quiet_) draw(last_done_, true);
}

void Progress::draw(int done, bool final_line) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fps = elapsed > 0 ? done / elapsed : 0.0;
  char line[256];
  if (total_ > 0) {
    constexpr int kWidth = 30;
    const int filled = std::min(kWidth, done * kWidth / total_);
    std::string bar(filled, '#');
    bar.resize(kWidth, '.');
    const double left = fps > 0 ? (total_ - done) / fps : 0.0;
    std::snprintf(line, sizeof(line), "%s [%s] %d/%d  %.1f fps  %s %.0fs", label_.c_str(), bar.c_str(), done, total_,
                  fps, final_line ? "took" : "left", final_line ? elapsed : left);
  } else {
    std::snprintf(line, sizeof(line), "%s %d  %.1f fps  %.0fs", label_.c_str(), done, fps, elapsed);
  }
  if (tty_) {
    std::fprintf(stderr, "\r%s\033[K%s", line, final_line ? "\n" : "");
  } else {
    std::fprintf(stderr, "%s\n", line);
  }
  std::fflush(stderr);
}

}  // namespace facecap
