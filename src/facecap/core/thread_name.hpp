#pragma once
// Names the calling thread as `top -H`, `perf report --sort comm` and gdb
// show it, so that a profile tells capture, refinement and output apart.

namespace facecap {

// At most 15 characters are kept (the kernel's limit).
void name_this_thread(const char* name);

}  // namespace facecap
