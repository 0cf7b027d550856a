#pragma once
// Two synthetic performances alike in everything (expression, pose,
// lighting, skin) but the identity: a target, and a source whose frames are
// what a perfect swap of its frame 0 into the target's frames gives. For
// FaceSwapper's tests and benchmark.
#include "facecap/model/regions.hpp"
#include "facecap/swap/face_swapper.hpp"
#include "facecap/synth/performance.hpp"

namespace facecap::test {

struct TwoFaces {
  SynthPerformance target, source;
};

// `options` the target's (its seed draws the performance); the source's
// identity is drawn from `source_seed`.
inline TwoFaces two_faces(const FaceModel& model, SynthOptions options, uint64_t source_seed) {
  TwoFaces f{make_performance(model, options), {}};
  f.source = f.target;
  options.seed = source_seed;
  f.source.identity = make_performance(model, options).identity;
  return f;
}

// The face region of a performance's frame in camera space.
inline Positions face_points(const FaceModel& model, const SynthPerformance& p, const SynthFrame& frame) {
  return to_camera(model.evaluate(p.identity, frame.expression, regions::kFace), frame.pose);
}

// Frame `i` of a performance with its true parameters.
inline TargetFrame target_frame(const SynthPerformance& p, int i) {
  const SynthFrame& f = p.frames[size_t(i)];
  TargetFrame t;
  t.identity = p.identity;
  t.expression = f.expression;
  t.pose = f.pose;
  t.camera = p.camera;
  t.lighting = f.lighting;
  t.index = i;
  return t;
}

// Frame `i` of a performance as a source photo's reconstruction.
inline SourceFace source_face(const FaceModel& model, const SynthPerformance& p, int i) {
  const SynthFrame& f = p.frames[size_t(i)];
  SourceFace s;
  s.identity = p.identity;
  s.expression = f.expression;
  s.camera_points = face_points(model, p, f);
  s.camera = p.camera;
  s.lighting = f.lighting;
  return s;
}

}  // namespace facecap::test
