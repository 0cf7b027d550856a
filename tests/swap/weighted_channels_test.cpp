// One weight per texel, applied to every channel.
#include "facecap/swap/weighted_channels.hpp"

#include <gtest/gtest.h>

#include "facecap/core/error.hpp"

namespace facecap {

TEST(WeightedChannels, EveryChannelIsWeighedAndDividedByItsTexelsWeight) {
  cv::Mat value(1, 3, CV_32FC3);
  value.at<cv::Vec3f>(0, 0) = {1, 2, 3};
  value.at<cv::Vec3f>(0, 1) = {4, 5, 6};
  value.at<cv::Vec3f>(0, 2) = {7, 8, 9};
  const cv::Mat weight = (cv::Mat_<float>(1, 3) << 0.5f, 2.0f, 0.0f);
  cv::Mat weighted = times_weight(value, weight);
  EXPECT_EQ(weighted.at<cv::Vec3f>(0, 0), cv::Vec3f(0.5f, 1, 1.5f));
  EXPECT_EQ(weighted.at<cv::Vec3f>(0, 1), cv::Vec3f(8, 10, 12));
  EXPECT_EQ(weighted.at<cv::Vec3f>(0, 2), cv::Vec3f(0, 0, 0));
  // Back to the value where the weight is above `least`; divided by `least` below it.
  divide_by_weight(weighted, weight, 0.25f);
  EXPECT_EQ(weighted.at<cv::Vec3f>(0, 0), cv::Vec3f(1, 2, 3));
  EXPECT_EQ(weighted.at<cv::Vec3f>(0, 1), cv::Vec3f(4, 5, 6));
  EXPECT_EQ(weighted.at<cv::Vec3f>(0, 2), cv::Vec3f(0, 0, 0));
  cv::Mat one(1, 3, CV_32F, cv::Scalar(6));
  divide_by_weight(one, weight, 0.25f);
  EXPECT_EQ(one.at<float>(0, 2), 24.0f);
}

TEST(WeightedChannels, AWeightOfAnotherSizeOrTypeIsAnError) {
  const cv::Mat value(2, 2, CV_32FC3, cv::Scalar::all(1));
  EXPECT_THROW(times_weight(value, cv::Mat(2, 3, CV_32F, cv::Scalar(1))), Error);
  EXPECT_THROW(times_weight(value, cv::Mat(2, 2, CV_8U, cv::Scalar(1))), Error);
  cv::Mat bytes(2, 2, CV_8UC3, cv::Scalar::all(1));
  EXPECT_THROW(divide_by_weight(bytes, cv::Mat(2, 2, CV_32F, cv::Scalar(1)), 1e-6f), Error);
}

}  // namespace facecap
