#pragma once
// Ctrl-C and SIGTERM stop long jobs cleanly: the first signal sets a flag that
// the frame loops poll; they throw facecap::Error("interrupted"), so
// destructors remove temporary outputs and nothing half-written remains. A
// second signal exits at once, removing the registered temporary files
// (temp_files.hpp) first.
namespace facecap {

void install_interrupt_handler();
bool interrupted();
// Throws facecap::Error when an interrupt was requested.
void throw_if_interrupted();

// A live input (a camera) ends only when the user says so: while this is
// set, the first signal ends the input rather than the job (the handler says
// so), and the job writes what it captured. The capture sets it for a camera.
void set_interrupt_ends_input(bool ends_input);
// Forgets an interrupt that was handled by ending the input, so that the
// rest of the job (writing its files) runs, and a later signal is a first one.
void clear_interrupt();

}  // namespace facecap
