#include "facecap/core/interrupt.hpp"

#include <unistd.h>
#include <csignal>
#include <cstdlib>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_files.hpp"

namespace facecap {

namespace {

volatile std::sig_atomic_t g_interrupted = 0;
volatile std::sig_atomic_t g_ends_input = 0;

extern "C" void on_signal(int) {
  if (g_interrupted) {
    remove_registered_temp_files();  // the destructors that would remove them do not run
    std::_Exit(130);
  }
  g_interrupted = 1;
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
