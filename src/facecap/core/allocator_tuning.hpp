#pragma once

namespace facecap {

// Keeps large heap blocks inside the process instead of returning them to the
// kernel on every free. glibc serves blocks above 128 KiB (adaptively up to
// 32 MiB) with mmap and unmaps them on free, and trims per-thread arenas
// eagerly, so every per-frame image buffer of a video job page-faults afresh; on virtual machines a fault costs several
// microseconds and a 720p float image ~1k of them. Measured on the 2-core VM:
// cv::Mat::convertTo of a 175k-pixel face window 7-14 ms before, 0.35 ms after.
// Call once at program start, before worker threads allocate.
void keep_large_allocations_resident();

}  // namespace facecap
