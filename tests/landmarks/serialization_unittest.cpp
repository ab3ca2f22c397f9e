/* Save/load of CLandmarkDatabase through MRPT serialization: bit-exact round
 * trip of landmarks, keypoints, descriptors and patches; bad files throw. */
#include <gtest/gtest.h>
#include <roislam/features/CFeatureExtractor.h>
#include <roislam/landmarks/CLandmarkDatabase.h>
#include <roislam/testing/TestData.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "SyntheticScene.h"

using namespace roislam;
using namespace roislam::landmarks;

namespace
{
CLandmark landmarkOf(unsigned seed, features::EFeatureType type)
{
  const cv::Rect box(100, 100, 220, 180);
  const cv::Mat img = test::onCanvas(test::texturePatch(seed), box.tl());
  features::CFeatureExtractor::TOptions o;
  o.feature_type = type;
  cv::Mat grey;
  cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY);
  CLandmark lm;
  lm.features = features::CFeatureExtractor(o).extract(grey).subset(box);
  lm.box = box;
  lm.imageSize = img.size();
  lm.patch = img(box).clone();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < lm.features.size(); ++i)
    lm.featurePoints.push_back(
        i % 7 == 3 ? mrpt::math::TPoint3D(nan, nan, nan)
                   : mrpt::math::TPoint3D(0.001 * i, -0.002 * i, 1.0 + 1e-3 * seed));
  lm.hasPositionCamera = true;
  lm.positionWorld = {1.0, 2.0 * seed, 3.0};
  lm.hasPositionWorld = seed % 2 == 0;
  for (int i = 0; i < 3; ++i)
  {
    TLandmarkSighting s;
    s.frame = 10 * seed + i;
    s.timestamp = 1305031229.528748 + i / 30.0;
    s.box = cv::Rect(box.x + i, box.y - i, box.width, box.height);
    s.position = {0.5, 0.25 * i, 2.0};
    s.hasPosition = i != 1;
    s.inliers = 20 + i;
    lm.sightings.push_back(s);
  }
  return lm;
}

bool sameMat(const cv::Mat& a, const cv::Mat& b)
{
  if (a.type() != b.type() || a.size() != b.size())
    return false;
  if (a.empty())
    return true;
  return cv::countNonZero(a.reshape(1) != b.reshape(1)) == 0;
}

void expectSame(const CLandmark& a, const CLandmark& b)
{
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.features.type, b.features.type);
  ASSERT_EQ(a.features.keypoints.size(), b.features.keypoints.size());
  for (std::size_t i = 0; i < a.features.keypoints.size(); ++i)
  {
    const auto &p = a.features.keypoints[i], &q = b.features.keypoints[i];
    EXPECT_EQ(p.pt, q.pt);
    EXPECT_EQ(p.size, q.size);
    EXPECT_EQ(p.angle, q.angle);
    EXPECT_EQ(p.response, q.response);
    EXPECT_EQ(p.octave, q.octave);
    EXPECT_EQ(p.class_id, q.class_id);
  }
  EXPECT_TRUE(sameMat(a.features.descriptors, b.features.descriptors));
  ASSERT_EQ(a.featurePoints.size(), b.featurePoints.size());
  EXPECT_EQ(
      std::memcmp(
          a.featurePoints.data(), b.featurePoints.data(),
          a.featurePoints.size() * sizeof(mrpt::math::TPoint3D)),
      0);  // bit-exact, NaNs included
  EXPECT_TRUE(sameMat(a.patch, b.patch));
  EXPECT_EQ(a.box, b.box);
  EXPECT_EQ(a.imageSize, b.imageSize);
  EXPECT_EQ(a.positionCamera, b.positionCamera);
  EXPECT_EQ(a.hasPositionCamera, b.hasPositionCamera);
  EXPECT_EQ(a.positionWorld, b.positionWorld);
  EXPECT_EQ(a.hasPositionWorld, b.hasPositionWorld);
  ASSERT_EQ(a.sightings.size(), b.sightings.size());
  for (std::size_t i = 0; i < a.sightings.size(); ++i)
  {
    EXPECT_EQ(a.sightings[i].frame, b.sightings[i].frame);
    EXPECT_EQ(a.sightings[i].timestamp, b.sightings[i].timestamp);
    EXPECT_EQ(a.sightings[i].box, b.sightings[i].box);
    EXPECT_EQ(a.sightings[i].position, b.sightings[i].position);
    EXPECT_EQ(a.sightings[i].hasPosition, b.sightings[i].hasPosition);
    EXPECT_EQ(a.sightings[i].inliers, b.sightings[i].inliers);
  }
}
}  // namespace

class SerializationRoundTrip : public ::testing::TestWithParam<features::EFeatureType>
{
};

TEST_P(SerializationRoundTrip, SaveLoadIsBitExact)
{
  CLandmarkDatabase db;
  for (unsigned seed = 1; seed <= 3; ++seed)
    db.add(landmarkOf(seed, GetParam()));
  const std::string dir = roislam::testing::makeTempDir("landmarks_ser");
  const std::string file = dir + "/landmarks.db";
  db.save(file);
  EXPECT_FALSE(std::filesystem::exists(file + ".tmp"));

  CLandmarkDatabase back;
  back.load(file);
  ASSERT_EQ(back.size(), db.size());
  for (std::size_t i = 0; i < db.size(); ++i)
    expectSame(db.landmarks()[i], back.landmarks()[i]);

  // The loaded database still recalls: its descriptors are usable as stored.
  const auto q = back.query(back.landmark(1).features, back.landmark(1).box, {640, 480});
  ASSERT_TRUE(q.landmarkId);
  EXPECT_EQ(*q.landmarkId, 1);
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Features, SerializationRoundTrip,
    ::testing::Values(features::EFeatureType::ORB, features::EFeatureType::SIFT));

TEST(Serialization, SingleLandmarkThroughAnArchive)
{
  const CLandmark a = landmarkOf(4, features::EFeatureType::ORB);
  const std::string dir = roislam::testing::makeTempDir("landmarks_ser");
  CLandmarkDatabase db;
  db.add(a);
  db.save(dir + "/one.db");
  CLandmarkDatabase back;
  back.load(dir + "/one.db");
  ASSERT_EQ(back.size(), 1u);
  CLandmark expected = a;
  expected.id = 0;
  expectSame(expected, back.landmark(0));
  std::filesystem::remove_all(dir);
}

TEST(Serialization, BadFilesThrowNamingTheFile)
{
  const std::string dir = roislam::testing::makeTempDir("landmarks_ser");
  CLandmarkDatabase db;
  try
  {
    db.load(dir + "/missing.db");
    FAIL() << "no exception";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("missing.db"), std::string::npos) << e.what();
  }
  {
    std::ofstream f(dir + "/garbage.db");
    f << "this is not an MRPT archive at all";
  }
  try
  {
    db.load(dir + "/garbage.db");
    FAIL() << "no exception";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("garbage.db"), std::string::npos) << e.what();
  }
  EXPECT_THROW(db.save(dir + "/no/such/folder/x.db"), std::runtime_error);
  std::filesystem::remove_all(dir);
}
