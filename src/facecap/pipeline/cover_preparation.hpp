#pragma once
// The part of finding a face's covers that needs only the frame, the
// tracked face and its lighting (frame_preparation.hpp), run on a
// refinement stage's second thread beside the edit of the frame before:
// the edit's thread is the pipeline's slowest.
#include "facecap/pipeline/refine_stage.hpp"
#include "facecap/swap/frame_preparation.hpp"

namespace facecap {

// Sets the stage's prepare hook: each tracked frame's PreparedFrame into
// RefinedFrame::prepared (nothing for a lost frame); a shot's first frame
// resets `preparation` first. `preparation` outlives the stage's threads.
void prepare_covers_beside(RefineStage& stage, FramePreparation& preparation);

// The frame's PreparedFrame, where the hook made one.
const PreparedFrame* prepared_covers(const RefinedFrame& frame);

}  // namespace facecap
