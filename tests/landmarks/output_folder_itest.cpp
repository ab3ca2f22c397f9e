/* roi-landmarks' output folder is complete or absent: refused when not empty
 * (unless overwrite, which replaces only our own files), untouched by a run
 * that fails, and the annotated rawlog inside it moves with it. */
#include <gtest/gtest.h>
#include <roislam/landmarks/CRoiLandmarksApp.h>
#include <roislam/testing/FolderListing.h>
#include <roislam/testing/TestData.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using roislam::landmarks::CRoiLandmarksApp;

namespace
{
std::string errorOf(const CRoiLandmarksApp::TArguments& a)
{
  try
  {
    CRoiLandmarksApp(a).run();
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(RoiLandmarksOutput, CompleteOrAbsentAndNeverMixed)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string tmp = roislam::testing::makeTempDir("lm_output");
  CRoiLandmarksApp::TArguments a;
  a.input = seq;
  a.outputDir = tmp + "/out";
  a.outputRawlog = tmp + "/out/rawlog/annotated.rawlog";
  a.maxFrames = 12;
  EXPECT_EQ(errorOf(a), "");
  const auto first = roislam::testing::outputListing(a.outputDir);
  EXPECT_EQ(
      first, (std::vector<std::string>{
                 "frames.csv", "landmarks", "landmarks.db", "rawlog", "summary.json"}));
  EXPECT_TRUE(fs::is_regular_file(a.outputDir + "/rawlog/annotated.rawlog"));
  EXPECT_TRUE(fs::is_directory(a.outputDir + "/rawlog/annotated_Images"));
  EXPECT_EQ(roislam::testing::outputListing(tmp), std::vector<std::string>{"out"});

  // Again: refused without overwrite, the earlier output untouched.
  const std::string e = errorOf(a);
  EXPECT_NE(e.find("output dir " + a.outputDir + ": not empty"), std::string::npos) << e;
  EXPECT_EQ(roislam::testing::outputListing(a.outputDir), first);
  // With overwrite, but no annotated rawlog this time: the old one is gone.
  a.overwrite = true;
  a.outputRawlog.reset();
  EXPECT_EQ(errorOf(a), "");
  EXPECT_EQ(
      roislam::testing::outputListing(a.outputDir),
      (std::vector<std::string>{"frames.csv", "landmarks", "landmarks.db", "summary.json"}));

  // A run that fails (no such input) leaves the earlier output as it was.
  const auto before = roislam::testing::outputListing(a.outputDir);
  a.input = tmp + "/missing";
  EXPECT_NE(errorOf(a).find("missing"), std::string::npos);
  EXPECT_EQ(roislam::testing::outputListing(a.outputDir), before);
  EXPECT_EQ(roislam::testing::outputListing(tmp), std::vector<std::string>{"out"});

  // A file we do not write is never replaced.
  std::ofstream(a.outputDir + "/notes.txt") << "precious";
  a.input = seq;
  EXPECT_NE(errorOf(a).find("holds notes.txt"), std::string::npos);
  fs::remove_all(tmp);
}
