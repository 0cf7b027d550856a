#pragma once
// Ctrl-C and SIGTERM stop long jobs cleanly: the first signal sets a flag that
// the frame loops poll; they throw facecap::Error("interrupted"), so
// destructors remove temporary outputs and nothing half-written remains. A
// second signal exits at once.
namespace facecap {

void install_interrupt_handler();
bool interrupted();
// Throws facecap::Error when an interrupt was requested.
void throw_if_interrupted();

}  // namespace facecap
