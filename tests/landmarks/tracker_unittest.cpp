/* CRoiLandmarkTracker: the dissertation's flow on a synthetic sequence: no ROI
 * -> "NaN"; a first ROI is not confirmed ("no new ROI"); re-found in the next
 * frame it becomes landmark 0; a different scene gives landmark 1; going back
 * recalls landmark 0 instead of storing a duplicate. */
#include <gtest/gtest.h>
#include <roislam/landmarks/CRoiLandmarkTracker.h>

#include <cmath>

#include "SyntheticScene.h"

using namespace roislam;
using namespace roislam::landmarks;

TEST(RoiLandmarkTracker, DissertationFlowOnASyntheticSequence)
{
  const cv::Mat blank(480, 640, CV_8UC3, cv::Scalar(128, 128, 128));
  const cv::Mat a = test::onCanvas(test::texturePatch(11), {150, 120});
  const cv::Mat b = test::onCanvas(test::texturePatch(12), {260, 200});
  std::vector<cv::Mat> images{
      blank,
      a,
      test::warped(a, 2, {5, 2}),
      test::warped(a, 4, {10, 4}),
      b,
      test::warped(b, -3, {-6, 3}),
      test::warped(a, -5, {-20, 10}),
      test::warped(a, -6, {-24, 12})};
  CRoiLandmarkTracker tracker;
  std::vector<TFrameResult> r;
  for (std::size_t i = 0; i < images.size(); ++i)
    r.push_back(tracker.process(test::makeFrame(i, images[i])));

  EXPECT_EQ(r[0].status, ERoiStatus::NoRoi);
  EXPECT_EQ(r[0].statusText(), "NaN");
  EXPECT_FALSE(r[0].roi);

  EXPECT_EQ(r[1].status, ERoiStatus::NotConfirmed);  // no ROI in the previous frame to re-find
  EXPECT_EQ(r[1].statusText(), "no new ROI");
  ASSERT_TRUE(r[1].roi);
  EXPECT_TRUE((r[1].roi.value() & cv::Rect(150, 120, 220, 180)).area() > 0.8 * 220 * 180);

  ASSERT_EQ(r[2].status, ERoiStatus::Landmark);
  EXPECT_EQ(r[2].landmarkId, 0);
  EXPECT_TRUE(r[2].newLandmark);
  EXPECT_EQ(r[2].statusText(), "landmark 0");
  EXPECT_GE(r[2].matches, 10);
  EXPECT_LE(r[2].falseMatches, r[2].matches);
  EXPECT_NEAR(r[2].depthMedian, 1.5, 1e-6);
  ASSERT_TRUE(r[2].roiPosition);
  EXPECT_NEAR(r[2].roiPosition->z, 1.5, 1e-6);

  ASSERT_EQ(r[3].status, ERoiStatus::Landmark);
  EXPECT_EQ(r[3].landmarkId, 0);
  EXPECT_FALSE(r[3].newLandmark);
  EXPECT_GE(r[3].recallInliers, 10);

  EXPECT_EQ(r[4].status, ERoiStatus::NotConfirmed);  // scene change: not in the previous frame
  ASSERT_EQ(r[5].status, ERoiStatus::Landmark);
  EXPECT_EQ(r[5].landmarkId, 1);
  EXPECT_TRUE(r[5].newLandmark);

  EXPECT_EQ(r[6].status, ERoiStatus::NotConfirmed);
  ASSERT_EQ(r[7].status, ERoiStatus::Landmark);
  EXPECT_EQ(r[7].landmarkId, 0);  // recalled, not a duplicate
  EXPECT_FALSE(r[7].newLandmark);

  const auto& db = tracker.database();
  ASSERT_EQ(db.size(), 2u);
  EXPECT_EQ(db.landmark(0).sightings.size(), 3u);
  EXPECT_EQ(db.landmark(0).sightings.back().frame, 7u);
  EXPECT_TRUE(db.landmark(0).hasPositionCamera);
  EXPECT_FALSE(db.landmark(0).hasPositionWorld);  // no pose given
  EXPECT_FALSE(db.landmark(0).patch.empty());
  for (const auto& x : r)
    EXPECT_GT(x.seconds, 0);
}

TEST(RoiLandmarkTracker, WithoutConfirmationAndWithAPose)
{
  TPipelineOptions o;
  o.tracker.confirm = false;
  CRoiLandmarkTracker tracker(o);
  const cv::Mat a = test::onCanvas(test::texturePatch(21), {150, 120});
  const mrpt::poses::CPose3D pose(1, 2, 3, 0, 0, 0);
  const auto r = tracker.process(test::makeFrame(0, a), pose);
  ASSERT_EQ(r.status, ERoiStatus::Landmark);  // stored at first sight
  EXPECT_TRUE(r.newLandmark);
  const auto& lm = tracker.database().landmark(0);
  ASSERT_TRUE(lm.hasPositionWorld);
  EXPECT_NEAR(lm.positionWorld.z, 3 + 1.5, 1e-6);
  EXPECT_NEAR(lm.positionWorld.x, 1 + lm.positionCamera.x, 1e-9);

  tracker.resetSequence();
  const auto again = tracker.process(test::makeFrame(1, test::warped(a, 3, {4, 4})), pose);
  EXPECT_EQ(again.landmarkId, 0);
  EXPECT_FALSE(again.newLandmark);
}
