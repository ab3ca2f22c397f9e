/* Configuration: the shipped ini loads; unknown keys and bad values are
 * rejected with the file, section and key in the message; the key-check
 * helper works on any CLoadableOptions. */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/landmarks/TPipelineOptions.h>
#include <roislam/testing/TestData.h>

#include <algorithm>

using namespace roislam;
using namespace roislam::landmarks;

namespace
{
/** The message of the exception thrown by loading ini text, or "". */
std::string loadError(const std::string& text)
{
  mrpt::config::CConfigFileMemory cfg(text);
  TPipelineOptions o;
  try
  {
    o.load(cfg, "test.ini");
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part)
{
  return s.find(part) != std::string::npos;
}
}  // namespace

TEST(Config, ShippedIniLoads)
{
  TPipelineOptions o;
  ASSERT_NO_THROW(o.loadFromFile(roislam::testing::sourceDir() + "/config/roi_landmarks.ini"));
  EXPECT_EQ(o.roi.preset, "big");
  EXPECT_EQ(o.features.feature_type, features::EFeatureType::ORB);
  EXPECT_DOUBLE_EQ(o.scoring.match_radius, 0.25);
  EXPECT_EQ(o.database.max_candidates, 8);
  EXPECT_TRUE(o.tracker.confirm);
}

TEST(Config, SavedOptionsLoadBackAndPassTheKeyCheck)
{
  TPipelineOptions a;
  a.database.max_candidates = 3;
  a.scoring.match_radius = 0.4;
  a.tracker.max_depth = 5;
  a.observations.sensor_pose = mrpt::poses::CPose3D(0.1, 0.2, 0.3, 0.4, 0.5, 0.6);
  mrpt::config::CConfigFileMemory cfg;
  a.save(cfg);
  TPipelineOptions b;
  ASSERT_NO_THROW(b.load(cfg, "mem"));
  EXPECT_EQ(b.database.max_candidates, 3);
  EXPECT_DOUBLE_EQ(b.scoring.match_radius, 0.4);
  EXPECT_DOUBLE_EQ(b.tracker.max_depth, 5);
  EXPECT_NEAR(b.observations.sensor_pose.yaw(), 0.4, 1e-6);
  EXPECT_NEAR(b.observations.sensor_pose.z(), 0.3, 1e-6);
}

TEST(Config, UnknownKeysNameFileSectionAndKey)
{
  const std::string e1 = loadError("[LandmarkDatabase]\nmax_candidatse = 3\n");
  EXPECT_TRUE(contains(e1, "test.ini")) << e1;
  EXPECT_TRUE(contains(e1, "[LandmarkDatabase]")) << e1;
  EXPECT_TRUE(contains(e1, "unknown key 'max_candidatse'")) << e1;

  const std::string e2 = loadError("[FeatureExtractor]\nfeature_typ = sift\n");
  EXPECT_TRUE(contains(e2, "[FeatureExtractor] unknown key 'feature_typ'")) << e2;

  const std::string e3 = loadError("[RoiLandmarks]\nmatch_radius = 0.3\n");  // wrong section
  EXPECT_TRUE(contains(e3, "[RoiLandmarks] unknown key 'match_radius'")) << e3;

  // Sections that are not ours are left alone (shared ini files).
  EXPECT_EQ(loadError("[SomeoneElse]\nwhatever = 1\n"), "");
  // Keys are case-insensitive, as MRPT's reader.
  EXPECT_EQ(loadError("[LandmarkScoring]\nMatch_Radius = 0.3\n"), "");
}

TEST(Config, BadValuesNameSectionAndKey)
{
  const std::string e1 = loadError("[LandmarkScoring]\nmatch_radius = -1\n");
  EXPECT_TRUE(contains(e1, "[LandmarkScoring] match_radius")) << e1;
  const std::string e1b = loadError("[LandmarkScoring]\nrecall_position = centre\n");
  EXPECT_TRUE(contains(e1b, "[LandmarkScoring] recall_position")) << e1b;
  const std::string e2 = loadError("[RoiLandmarks]\nmax_depth = far\n");
  EXPECT_TRUE(contains(e2, "[RoiLandmarks] max_depth")) << e2;
  const std::string e3 = loadError("[RoiLandmarks]\nconfirm = maybe\n");
  EXPECT_TRUE(contains(e3, "[RoiLandmarks] confirm")) << e3;
  const std::string e4 = loadError("[ObservationProcessor]\nsensor_pose = [1 2]\n");
  EXPECT_TRUE(contains(e4, "[ObservationProcessor] sensor_pose")) << e4;
  const std::string e5 = loadError("[LandmarkDatabase]\nmax_candidates = 2.5\n");
  EXPECT_TRUE(contains(e5, "[LandmarkDatabase] max_candidates")) << e5;
  const std::string e6 = loadError("[ObservationProcessor]\nlandmark_points = both\n");
  EXPECT_TRUE(contains(e6, "[ObservationProcessor] landmark_points")) << e6;
  const std::string e7 =
      loadError("[ObservationProcessor]\npoints_per_sighting = 8\nmax_points_per_landmark = 4\n");
  EXPECT_TRUE(contains(e7, "[ObservationProcessor] max_points_per_landmark")) << e7;
  const std::string e8 = loadError("[ObservationProcessor]\npoint_max_residual = 0\n");
  EXPECT_TRUE(contains(e8, "[ObservationProcessor] point_max_residual")) << e8;
}

TEST(Config, MissingFileIsNamed)
{
  TPipelineOptions o;
  try
  {
    o.loadFromFile("/nonexistent/dir/x.ini");
    FAIL();
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_TRUE(contains(e.what(), "/nonexistent/dir/x.ini")) << e.what();
  }
}

TEST(Config, KeyCheckHelperOnAnyOptions)
{
  const auto keys = roislam::common::knownIniKeys(CLandmarkScorer::TOptions());
  EXPECT_EQ(keys.size(), 4u);
  EXPECT_TRUE(std::find(keys.begin(), keys.end(), "match_radius") != keys.end());
  mrpt::config::CConfigFileMemory cfg("[S]\nmatch_radius = 1\nbogus = 2\n");
  try
  {
    roislam::common::checkIniKeys(cfg, "S", keys, "f.ini");
    FAIL();
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_STREQ(e.what(), "ini f.ini: [S] unknown key 'bogus'");
  }
  EXPECT_NO_THROW(roislam::common::checkIniKeys(cfg, "Absent", keys, "f.ini"));
}
