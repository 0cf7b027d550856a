#pragma once
// Where a face mesh opens at the eyes: the loops of its open boundary
// around them. The face region's skin (FACTS.md's narrow face) ends just
// behind the lids, where they turn in toward the eyeball (seen from the
// front, the upper lid's edge hides the loop's top by 2-3 mm); what lies
// inside, the skin does not model. The loop moves with the lids: ICT's
// eyeBlink at 1 makes it two thirds as tall, eyeWide taller.
#include <array>
#include <vector>

#include "facecap/core/mesh.hpp"
#include "facecap/model/face_model.hpp"

namespace facecap {

// Each eye's opening as a loop of vertices of `skin` (face-region vertex
// numbers), eye 0 (iBUG 36-41) then eye 1 (42-47): the boundary loop whose
// centroid on the mean face lies nearest that eye's six landmarks'. Empty
// where the skin's boundary has no loop but its outline and ones nearer
// the other eye.
std::array<std::vector<int>, 2> eye_margin_loops(const FaceModel& model, const std::vector<Triangle>& skin);

}  // namespace facecap
