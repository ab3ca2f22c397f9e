/* roi-landmarks end to end: the app class on the synthetic textured sequence
 * (ground truth from the simulator) and on the shared TUM sequence (skipped
 * when absent); the executable's error path. */
#include <gtest/gtest.h>
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
        "feature", "roi_preset", "input"})
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
  ASSERT_TRUE(s.precision);
  EXPECT_GE(*s.precision, 0.8);
  ASSERT_TRUE(s.recall);
  EXPECT_GE(*s.recall, 0.6);
  checkOutputs(out, s);
  EXPECT_GT(fs::file_size(out + "/annotated.rawlog"), 100u);
  EXPECT_TRUE(fs::is_directory(out + "/annotated_Images"));
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
  ASSERT_TRUE(s.precision);
  ASSERT_TRUE(s.recall);
  EXPECT_GE(*s.precision, 0.8);
  EXPECT_GE(*s.recall, 0.7);
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
                    "/bad.ini: [LandmarkDatabase] unknown key 'max_candidats'\n");

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
