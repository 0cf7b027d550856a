#include "facecap/model/eye_margins.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "facecap/model/regions.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

// The face region's triangles on the narrow face (FACTS.md's skin).
std::vector<Triangle> narrow_face_triangles(const FaceModel& model) {
  std::vector<Triangle> skin;
  for (const Triangle& t : model.region_mesh(regions::kFace).triangles)
    if (std::all_of(t.begin(), t.end(), [](int v) { return v <= regions::kNarrowFace.last_vertex; })) skin.push_back(t);
  return skin;
}

// The loop's outline seen from the front (x, y).
std::vector<Vec2f> front_view(const Positions& points, const std::vector<int>& loop) {
  std::vector<Vec2f> outline;
  for (const int v : loop) outline.emplace_back(points(0, v), points(1, v));
  return outline;
}

float height(const std::vector<Vec2f>& outline) {
  float low = 1e9f, high = -1e9f;
  for (const Vec2f& p : outline) low = std::min(low, p.y()), high = std::max(high, p.y());
  return high - low;
}

// Whether `p` lies inside the polygon (even-odd rule).
bool inside(const std::vector<Vec2f>& polygon, const Vec2f& p) {
  bool in = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2f &a = polygon[i], &b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()))
      in = !in;
  }
  return in;
}

}  // namespace

TEST(EyeMargins, EachEyesLoopGoesRoundItsEyeAndMovesWithTheLids) {
  FACECAP_REQUIRE_MODEL(model);
  const std::array<std::vector<int>, 2> margins = eye_margin_loops(*model, narrow_face_triangles(*model));
  const Eigen::VectorXf none;
  const Eigen::VectorXf identity = model->identity_shape(none, regions::kFace);
  const Positions open = model->with_expression(identity, none, regions::kFace);
  // Both eyes shut (eyeBlink) and opened wide (eyeWide) at 1.
  auto both = [&](const std::string& shape) {
    Eigen::VectorXf w = Eigen::VectorXf::Zero(model->num_expressions());
    for (const char* side : {"_L", "_R"}) {
      EXPECT_GE(model->expression_index(shape + side), 0) << shape << side;
      w[std::max(0, model->expression_index(shape + side))] = 1;
    }
    return model->with_expression(identity, w, regions::kFace);
  };
  const Positions shut = both("eyeBlink"), wide = both("eyeWide");
  for (int e = 0; e < 2; ++e) {
    ASSERT_GE(margins[e].size(), 12u) << "eye " << e;
    const std::vector<Vec2f> outline = front_view(open, margins[e]);
    // The centre of each eye's six landmark vertices inside its own loop,
    // not the other's.
    for (int eye = 0; eye < 2; ++eye) {
      Vec2f centre = Vec2f::Zero();
      for (int i = 36 + 6 * eye; i < 42 + 6 * eye; ++i) {
        const int v = model->landmarks.vertices[size_t(i)];
        centre += Vec2f(open(0, v), open(1, v)) / 6.0f;
      }
      EXPECT_EQ(inside(outline, centre), eye == e) << "eye " << eye << "'s centre against eye " << e << "'s margin";
    }
    // It moves with the lids: shut, the opening is two thirds as tall
    // (the loop runs behind the lids, where they turn in toward the
    // eyeball, and the lower lid hardly moves); wide, taller.
    const float open_height = height(outline);
    EXPECT_LT(height(front_view(shut, margins[e])), 0.75f * open_height) << "eye " << e;
    EXPECT_GT(height(front_view(wide, margins[e])), 1.05f * open_height) << "eye " << e;
  }
}

}  // namespace facecap
