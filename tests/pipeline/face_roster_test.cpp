#include "facecap/pipeline/face_roster.hpp"

#include <gtest/gtest.h>

namespace facecap {

TEST(FaceRoster, AFaceIsFollowedWithinHalfItsSizeOfAFollowedFace) {
  const std::vector<Box> followed = {{100, 100, 80, 100}};  // centre (140, 150), size 90
  EXPECT_TRUE(is_followed({110, 110, 70, 70}, followed));   // centre (145, 145)
  EXPECT_TRUE(is_followed({140, 100, 80, 80}, followed));   // centre (180, 140): 41 px away
  EXPECT_FALSE(is_followed({150, 100, 80, 80}, followed));  // centre (190, 140): 51 px away
  EXPECT_FALSE(is_followed({110, 110, 70, 70}, {}));
}

TEST(FaceRoster, MatchesPointsToTheirNearestFacesNearestPairsFirst) {
  const std::vector<FaceDetection> faces = {{{0, 0, 20, 20}, 1.0}, {{100, 0, 20, 20}, 1.0}};  // centres x = 10, 110
  // The nearest pair (the second point and the first face) goes first, even
  // though the first point is nearer the first face than the second.
  const std::vector<int> match = match_nearest({{40, 10}, {20, 10}}, faces);
  ASSERT_EQ(match.size(), 2u);
  EXPECT_EQ(match[1], 0);
  EXPECT_EQ(match[0], 1);
  // More points than faces: the farthest point gets none.
  EXPECT_EQ(match_nearest({{10, 10}, {500, 10}, {100, 10}}, faces), (std::vector<int>{0, -1, 1}));
  EXPECT_EQ(match_nearest({{10, 10}}, {}), (std::vector<int>{-1}));
}

}  // namespace facecap
