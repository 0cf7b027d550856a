#include "facecap/pipeline/cover_preparation.hpp"

#include <optional>

#include "facecap/core/parallel.hpp"

namespace facecap {

void prepare_covers_beside(RefineStage& stage, FramePreparation& preparation) {
  stage.on_prepare([&preparation](RefinedFrame& r) {
    if (r.starts_shot) preparation.reset();  // the edit starts again too
    if (!r.refinement || r.frame.image.empty()) return;
    // On 2 cores, on its own thread alone: the pool's worker is the edit's,
    // the pipeline's slowest stage. `bench swap --tracked-first` at 720p
    // (6 alternating pairs) 23.8-25.6 -> 25.9-27.4 fps, the same output (the
    // two flows, which ran on two cores, now one after the other). Where
    // there are more, the pool has workers to spare.
    std::optional<SerialScope> serial;
    if (worker_count() <= 2) serial.emplace();
    r.prepared = preparation.prepare(r.frame.image, r.coarse, r.camera, r.refinement->lighting, r.frame.index);
  });
}

const PreparedFrame* prepared_covers(const RefinedFrame& frame) {
  return std::any_cast<PreparedFrame>(&frame.prepared);
}

}  // namespace facecap
