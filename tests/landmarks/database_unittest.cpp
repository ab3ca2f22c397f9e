/* CLandmarkDatabase: recall / new / best-of-several logic, candidate voting and
 * the position prefilter, on synthetic textured patches and warped copies. */
#include <gtest/gtest.h>
#include <roislam/features/CFeatureExtractor.h>
#include <roislam/landmarks/CLandmarkDatabase.h>

#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <thread>
#include <vector>

#include "SyntheticScene.h"

using namespace roislam;
using namespace roislam::landmarks;

namespace
{
const cv::Rect kBox(100, 100, 220, 180);

features::TFeatureSet roiFeatures(
    const cv::Mat& bgr, const cv::Rect& box,
    features::EFeatureType type = features::EFeatureType::ORB)
{
  features::CFeatureExtractor::TOptions o;
  o.feature_type = type;
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  return features::CFeatureExtractor(o).extract(grey).subset(box);
}

CLandmark makeLandmark(unsigned seed, features::EFeatureType type = features::EFeatureType::ORB)
{
  const cv::Mat img = test::onCanvas(test::texturePatch(seed), kBox.tl());
  CLandmark lm;
  lm.features = roiFeatures(img, kBox, type);
  lm.box = kBox;
  lm.imageSize = img.size();
  lm.patch = img(kBox).clone();
  return lm;
}

/** Features of the seed's patch seen again: rotated, shifted, in a box around it. */
features::TFeatureSet seenAgain(
    unsigned seed, features::EFeatureType type = features::EFeatureType::ORB)
{
  const cv::Mat img =
      test::warped(test::onCanvas(test::texturePatch(seed), kBox.tl()), 7, {35, 20});
  return roiFeatures(img, cv::Rect(105, 95, 270, 230), type);
}
}  // namespace

TEST(LandmarkDatabase, EmptyDatabaseGivesNew)
{
  CLandmarkDatabase db;
  const auto q = db.query(seenAgain(1), kBox, {640, 480});
  EXPECT_FALSE(q.landmarkId);
  EXPECT_EQ(q.candidates, 0);
}

TEST(LandmarkDatabase, RecallsTheSameTextureAndRejectsADifferentOne)
{
  CLandmarkDatabase db;
  const auto lm = makeLandmark(1);
  ASSERT_GT(lm.features.size(), 50u);
  EXPECT_EQ(db.add(lm), 0);

  const auto same = db.query(seenAgain(1), kBox, {640, 480});
  ASSERT_TRUE(same.landmarkId);
  EXPECT_EQ(*same.landmarkId, 0);
  EXPECT_GE(same.inliers, 10);
  // The located box is the landmark's box moved by about the applied shift.
  EXPECT_NEAR(same.locatedBox.x + same.locatedBox.width / 2.0, kBox.x + kBox.width / 2.0 + 35, 25);

  const auto other = db.query(seenAgain(2), kBox, {640, 480});
  EXPECT_FALSE(other.landmarkId);
}

TEST(LandmarkDatabase, PicksTheRightLandmarkAmongSeveralWithAndWithoutVoting)
{
  for (int maxCandidates : {0, 2})
  {
    CLandmarkDatabase::TOptions o;
    o.max_candidates = maxCandidates;
    CLandmarkDatabase db(o, {}, {});
    for (unsigned seed = 1; seed <= 6; ++seed)
      db.add(makeLandmark(seed));
    ASSERT_EQ(db.size(), 6u);
    for (unsigned seed : {2u, 4u, 6u})
    {
      const auto q = db.query(seenAgain(seed), kBox, {640, 480});
      ASSERT_TRUE(q.landmarkId) << "seed " << seed << " max_candidates " << maxCandidates;
      EXPECT_EQ(*q.landmarkId, static_cast<int32_t>(seed - 1));
      EXPECT_TRUE(maxCandidates == 0 || q.candidates <= maxCandidates) << q.candidates;
    }
    EXPECT_FALSE(db.query(seenAgain(9), kBox, {640, 480}).landmarkId);
  }
}

TEST(LandmarkDatabase, WorksWithSiftToo)
{
  CLandmarkDatabase db;
  db.add(makeLandmark(1, features::EFeatureType::SIFT));
  db.add(makeLandmark(2, features::EFeatureType::SIFT));
  const auto q = db.query(seenAgain(2, features::EFeatureType::SIFT), kBox, {640, 480});
  ASSERT_TRUE(q.landmarkId);
  EXPECT_EQ(*q.landmarkId, 1);
  // Mixing feature types is an error, not a silent miss.
  EXPECT_THROW(db.query(seenAgain(2), kBox, {640, 480}), std::invalid_argument);
  EXPECT_THROW(db.add(makeLandmark(3)), std::invalid_argument);
}

TEST(LandmarkDatabase, PositionPrefilterExcludesFarLandmarks)
{
  CLandmarkDatabase::TOptions o;
  o.prefilter_radius = 1.0;
  CLandmarkDatabase db(o, {}, {});
  auto lm = makeLandmark(1);
  lm.positionWorld = {5, 0, 0};
  lm.hasPositionWorld = true;
  db.add(lm);
  EXPECT_FALSE(
      db.query(seenAgain(1), kBox, {640, 480}, {}, mrpt::math::TPoint3D(0, 0, 0)).landmarkId);
  EXPECT_TRUE(
      db.query(seenAgain(1), kBox, {640, 480}, {}, mrpt::math::TPoint3D(4.5, 0, 0)).landmarkId);
  EXPECT_TRUE(db.query(seenAgain(1), kBox, {640, 480}).landmarkId);
}

namespace
{
/** Points of features on a fronto-parallel plane at depth z (camera fx=525). */
std::vector<mrpt::math::TPoint3D> planePoints(const features::TFeatureSet& f, double z)
{
  std::vector<mrpt::math::TPoint3D> p;
  for (const auto& k : f.keypoints)
    p.emplace_back((k.pt.x - 319.5) * z / 525, (k.pt.y - 239.5) * z / 525, z);
  return p;
}
}  // namespace

TEST(LandmarkDatabase, ThreeDCheckAcceptsRigidMotionAndRejectsInconsistentDepth)
{
  CLandmarkDatabase db;
  auto lm = makeLandmark(1);
  lm.featurePoints = planePoints(lm.features, 1.5);
  lm.positionCamera = {0, 0, 1.5};
  lm.hasPositionCamera = true;
  db.add(lm);
  const auto again = seenAgain(1);

  // Consistent: the same plane (the image motion is a small rotation + shift
  // of a plane, so the 3-D points move rigidly up to pixel noise).
  const auto ok = db.query(again, kBox, {640, 480}, planePoints(again, 1.5));
  ASSERT_TRUE(ok.landmarkId);
  ASSERT_TRUE(ok.rigid);
  EXPECT_GE(ok.rigid->inliers, 10);
  EXPECT_LT(ok.rigid->rms, 0.05);

  // Inconsistent: the same texture but every other feature 1 m deeper (a
  // poster of the scene, say): no rigid motion explains a majority.
  auto bad = planePoints(again, 1.5);
  for (std::size_t i = 0; i < bad.size(); i += 2)
    bad[i].z += 1.0;
  for (std::size_t i = 0; i < bad.size(); i += 3)
    bad[i].x += 0.5;
  const auto rejected = db.query(again, kBox, {640, 480}, bad);
  EXPECT_FALSE(rejected.landmarkId);

  // No depth at all: the homography alone decides.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto noDepth = db.query(
      again, kBox, {640, 480}, std::vector<mrpt::math::TPoint3D>(again.size(), {nan, nan, nan}));
  ASSERT_TRUE(noDepth.landmarkId);
  EXPECT_FALSE(noDepth.rigid);
}

TEST(LandmarkDatabase, SightingsAndBadIds)
{
  CLandmarkDatabase db;
  db.add(makeLandmark(1));
  TLandmarkSighting s;
  s.frame = 7;
  db.addSighting(0, s);
  EXPECT_EQ(db.landmark(0).sightings.size(), 1u);
  EXPECT_EQ(db.landmark(0).sightings[0].frame, 7u);
  EXPECT_THROW(db.addSighting(3, s), std::out_of_range);
  EXPECT_THROW(db.landmark(-1), std::out_of_range);
}

TEST(LandmarkDatabase, ConcurrentQueriesShareTheLazyVoteIndex)
{
  // max_candidates 2 with 6 landmarks: every query votes, and the first ones
  // (concurrent here) build the vote index.
  CLandmarkDatabase::TOptions o;
  o.max_candidates = 2;
  CLandmarkDatabase db(o, {}, {});
  for (unsigned seed = 1; seed <= 6; ++seed)
    db.add(makeLandmark(seed));
  std::vector<features::TFeatureSet> queries;
  for (unsigned seed : {2u, 4u, 6u, 9u})
    queries.push_back(seenAgain(seed));
  std::vector<std::optional<int32_t>> got(queries.size() * 3);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < got.size(); ++t)
    threads.emplace_back(
        [&, t] {
          got[t] = db.query(queries[t % queries.size()], kBox, {640, 480}).landmarkId;
        });
  for (auto& th : threads)
    th.join();
  for (std::size_t t = 0; t < got.size(); ++t)
  {
    const auto sequential = db.query(queries[t % queries.size()], kBox, {640, 480}).landmarkId;
    EXPECT_EQ(got[t], sequential) << "thread " << t;
  }
  EXPECT_EQ(got[0], std::optional<int32_t>(1));
  EXPECT_FALSE(got[3]);
}
