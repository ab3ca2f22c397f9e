/* roi-landmarks end to end: the app class on the synthetic textured sequence
 * (ground truth from the simulator) and on the shared TUM sequence (skipped
 * when absent); the executable's error path. */
#include <gtest/gtest.h>
#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/serialization/CArchive.h>
#include <roislam/landmarks/CLandmarkDatabase.h>
#include <roislam/landmarks/CRoiLandmarksApp.h>
#include <roislam/testing/TestData.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace fs = std::filesystem;
using namespace roislam;
using namespace roislam::landmarks;

namespace
{
nlohmann::json readJson(const std::string& file)
{
  std::ifstream f(file);
  return nlohmann::json::parse(f);
}

std::size_t countLines(const std::string& file)
{
  std::ifstream f(file);
  std::size_t n = 0;
  for (std::string line; std::getline(f, line);)
    ++n;
  return n;
}

/** Checks the output folder's files agree with the summary. */
void checkOutputs(const std::string& out, const CRoiLandmarksApp::TSummary& s)
{
  const auto j = readJson(out + "/summary.json");
  EXPECT_EQ(j["frames"].get<std::size_t>(), s.frames);
  EXPECT_EQ(j["landmarks"].get<std::size_t>(), s.landmarks);
  EXPECT_EQ(countLines(out + "/frames.csv"), s.frames + 1);
  std::size_t patches = 0;
  for (const auto& e : fs::directory_iterator(out + "/landmarks"))
    patches += e.path().extension() == ".png";
  EXPECT_EQ(patches, s.landmarks);
  CLandmarkDatabase db;
  db.load(out + "/landmarks.db");
  EXPECT_EQ(db.size(), s.landmarks);
  for (const char* k :
       {"frames", "frames_with_roi", "landmarks", "recalls", "false_positives", "false_negatives",
        "precision", "recall", "matches_per_frame", "false_matches_per_frame", "duration_s", "fps",
        "feature", "roi_preset", "input", "recall_position", "alternative_scoring"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_FALSE(fs::exists(out + "/landmarks.partial"));
}
}  // namespace

TEST(RoiLandmarksApp, SyntheticTexturedSequence)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string out = roislam::testing::makeTempDir("roi_landmarks_synth");
  CRoiLandmarksApp::TArguments a;
  a.iniFile = roislam::testing::sourceDir() + "/config/roi_landmarks.ini";
  a.input = seq;
  a.outputDir = out;
  a.outputRawlog = out + "/annotated.rawlog";
  const auto s = CRoiLandmarksApp(a).run();
  EXPECT_GT(s.frames, 50u);
  EXPECT_GT(s.framesWithRoi, s.frames / 2);
  EXPECT_GE(s.landmarks, 1u);
  EXPECT_GT(s.recalls, 0u);
  // The simulator writes ground truth, so the scores exist and are sane.
  EXPECT_EQ(s.recallPosition, "landmark_point");
  ASSERT_TRUE(s.precision);
  EXPECT_GE(*s.precision, 0.9);
  ASSERT_TRUE(s.recall);
  EXPECT_GE(*s.recall, 0.8);
  EXPECT_EQ(s.altRecallPosition, "roi_median");
  ASSERT_TRUE(s.altPrecision);
  EXPECT_GE(*s.altPrecision, 0.7);
  checkOutputs(out, s);
  // The annotated rawlog: per frame a 3-D scan then its bearing-range
  // observation; external images load; landmark IDs exist in the database.
  ASSERT_TRUE(fs::is_directory(out + "/annotated_Images"));
  mrpt::img::CImage::setImagesPathBase(out + "/annotated_Images");
  mrpt::io::CFileGZInputStream in(out + "/annotated.rawlog");
  auto ar = mrpt::serialization::archiveFrom(in);
  std::size_t scans = 0, bearings = 0, measurements = 0;
  bool expectScan = true;
  for (;;)
  {
    mrpt::serialization::CSerializable::Ptr o;
    try
    {
      o = ar.ReadObject();
    }
    catch (const mrpt::serialization::CExceptionEOF&)
    {
      break;
    }
    if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(o))
    {
      EXPECT_TRUE(expectScan);
      if (scans == 0)
      {
        scan->load();
        EXPECT_EQ(scan->rangeImage.cols(), 640);
        EXPECT_EQ(scan->intensityImage.getWidth(), 640u);
        scan->unload();
      }
      ++scans;
    }
    else if (auto br = std::dynamic_pointer_cast<mrpt::obs::CObservationBearingRange>(o))
    {
      EXPECT_FALSE(expectScan);
      for (const auto& m : br->sensedData)
      {
        EXPECT_GE(m.landmarkID, 0);
        EXPECT_LT(static_cast<std::size_t>(m.landmarkID), s.landmarks);
        EXPECT_GT(m.range, 0.1f);
        ++measurements;
      }
      ++bearings;
    }
    else
      ADD_FAILURE() << "unexpected object " << o->GetRuntimeClass()->className;
    expectScan = !expectScan;
  }
  EXPECT_EQ(scans, s.frames);
  EXPECT_EQ(bearings, s.frames);
  EXPECT_GT(measurements, s.recalls / 2);
  fs::remove_all(out);
}

TEST(RoiLandmarksApp, SharedTumSequenceOrb)
{
  ROISLAM_REQUIRE_SHARED_TUM(seq);
  const std::string out = roislam::testing::makeTempDir("roi_landmarks_tum");
  CRoiLandmarksApp::TArguments a;
  a.iniFile = roislam::testing::sourceDir() + "/config/roi_landmarks.ini";
  a.input = seq;
  a.outputDir = out;
  a.feature = "orb";
  a.maxFrames = 120;
  const auto s = CRoiLandmarksApp(a).run();
  EXPECT_EQ(s.frames, 120u);
  EXPECT_GE(s.landmarks, 2u);
  EXPECT_LT(s.landmarks, 60u);
  // Landmark-point scores measure re-identification itself; the ROI-median
  // ones move with the ROI box.
  ASSERT_TRUE(s.precision);
  ASSERT_TRUE(s.recall);
  EXPECT_GE(*s.precision, 0.9);
  EXPECT_GE(*s.recall, 0.8);
  ASSERT_TRUE(s.altPrecision);
  ASSERT_TRUE(s.altRecall);
  EXPECT_GE(*s.altPrecision, 0.6);
  EXPECT_GE(*s.altRecall, 0.8);
  EXPECT_GT(s.matchesPerFrame, 10);
  checkOutputs(out, s);
  fs::remove_all(out);
}

TEST(RoiLandmarksApp, ExecutableReportsErrorsOnOneLine)
{
  const std::string exe = roislam::testing::binaryDir() + "/apps/roi-landmarks/roi-landmarks";
  if (!fs::exists(exe))
    GTEST_SKIP() << exe << " not built";
  const std::string out = roislam::testing::makeTempDir("roi_landmarks_err");
  {
    std::ofstream ini(out + "/bad.ini");
    ini << "[LandmarkDatabase]\nmax_candidats = 3\n";
  }
  const std::string cmd = exe + " --ini " + out + "/bad.ini --input " + out + " --output-dir " +
                          out + "/o 2> " + out + "/err.txt";
  const int rc = std::system(cmd.c_str());
  EXPECT_NE(rc, 0);
  std::ifstream f(out + "/err.txt");
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(
      ss.str(), "roi-landmarks: error: ini " + out +
                    "/bad.ini: [LandmarkDatabase] unknown key 'max_candidats' (line 2)\n");

  // A folder that is not a sequence fails cleanly, naming it.
  const std::string cmd2 =
      exe + " --input " + out + "/nothing --output-dir " + out + "/o 2> " + out + "/err2.txt";
  EXPECT_NE(std::system(cmd2.c_str()), 0);
  std::ifstream f2(out + "/err2.txt");
  std::string line;
  std::getline(f2, line);
  EXPECT_EQ(line.rfind("roi-landmarks: error: ", 0), 0u) << line;
  EXPECT_NE(line.find("nothing"), std::string::npos) << line;
  fs::remove_all(out);
}
