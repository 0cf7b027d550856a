#include "facecap/core/interrupt.hpp"

#include <unistd.h>
#include <atomic>
#include <csignal>
#include <cstdlib>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_files.hpp"

namespace facecap {

namespace {

// Atomics, not volatile sig_atomic_t: the handler runs on whichever thread
// the signal reaches (a decoder's, a stage's), and the frame loops that poll
// the flag run on others. Lock-free, so the handler may touch them.
static_assert(std::atomic<int>::is_always_lock_free);
std::atomic<int> g_interrupted{0};
std::atomic<int> g_ends_input{0};

extern "C" void on_signal(int) {
  if (g_interrupted.exchange(1) != 0) {
    remove_registered_temp_files();  // the destructors that would remove them do not run
    std::_Exit(130);
  }
  static const char cleanup[] = "\nfacecap: interrupted, cleaning up (press Ctrl-C again to quit at once)\n";
  static const char stop[] =
      "\nfacecap: stopping the camera; writing what was captured (press Ctrl-C again to quit at once)\n";
  [[maybe_unused]] const auto n = g_ends_input ? ::write(STDERR_FILENO, stop, sizeof(stop) - 1)
                                               : ::write(STDERR_FILENO, cleanup, sizeof(cleanup) - 1);
}

}  // namespace

void install_interrupt_handler() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool interrupted() { return g_interrupted != 0; }

void set_interrupt_ends_input(bool ends_input) { g_ends_input = ends_input ? 1 : 0; }

void clear_interrupt() { g_interrupted = 0; }

void throw_if_interrupted() {
  if (interrupted()) throw Error("interrupted");
}

}  // namespace facecap
