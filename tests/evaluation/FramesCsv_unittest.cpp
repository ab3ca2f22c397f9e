/* readFrameTimes: the keyframes' and frames' times of a run's frames.csv,
 * found by the header's column names; bad files give one line naming the
 * file and the line. */
#include <gtest/gtest.h>
#include <roislam/evaluation/FramesCsv.h>
#include <roislam/testing/TestData.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace
{
namespace fs = std::filesystem;
using roislam::evaluation::readFrameTimes;

std::string writeFile(const std::string& dir, const std::string& text)
{
  const std::string path = dir + "/frames.csv";
  std::ofstream(path) << text;
  return path;
}

std::string loadError(const std::string& dir, const std::string& text)
{
  const std::string file = writeFile(dir, text);
  try
  {
    readFrameTimes(file);
  }
  catch (const std::runtime_error& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(FramesCsv, KeyframesAndFramesByTheirColumns)
{
  const std::string dir = roislam::testing::makeTempDir("frames_csv");
  // Columns in another order than roi-graphslam writes them, an empty last
  // field, CRLF line ends and rows out of time order.
  const auto t = readFrameTimes(writeFile(
      dir,
      "index,keyframe,method,timestamp,extra\r\n"
      "0,0,initial,10.000001,\r\n"
      "1,,features,10.033334,x\r\n"
      "3,2,features,10.100001,\r\n"
      "2,1,icp,10.066667,\r\n"));
  ASSERT_EQ(t.keyframes.size(), 3u);
  EXPECT_DOUBLE_EQ(t.keyframes.at(0), 10.000001);
  EXPECT_DOUBLE_EQ(t.keyframes.at(1), 10.066667);
  EXPECT_DOUBLE_EQ(t.keyframes.at(2), 10.100001);
  ASSERT_EQ(t.frames.size(), 4u);
  EXPECT_TRUE(std::is_sorted(t.frames.begin(), t.frames.end()));
  EXPECT_DOUBLE_EQ(t.frames[1], 10.033334);
  fs::remove_all(dir);
}

TEST(FramesCsv, BadFilesGiveOneLineNamingFileAndLine)
{
  const std::string dir = roislam::testing::makeTempDir("frames_csv");
  const std::string file = dir + "/frames.csv";
  const auto expectError = [&](const std::string& text, const std::string& what)
  {
    const std::string err = loadError(dir, text);
    EXPECT_EQ(err.rfind(file, 0), 0u) << err;
    EXPECT_NE(err.find(what), std::string::npos) << err;
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
  };
  expectError("index,timestamp\n0,1.0\n", ":1: no 'keyframe' column");
  expectError("timestamp,keyframe\n1.0,0\n2.0\n", ":3: too few fields");
  expectError("timestamp,keyframe\nnan,0\n", ":2: timestamp 'nan' is not a number");
  expectError("timestamp,keyframe\n1.0,-1\n", ":2: keyframe '-1' is not a node number");
  expectError("timestamp,keyframe\n1.0,0\n2.0,0\n", ":3: keyframe 0 named twice");
  expectError("timestamp,keyframe\n", ": no frames");
  expectError("", ": no frames");
  fs::remove_all(dir);
  expectError("timestamp,keyframe\n1.0,0\n", ": cannot open");
}
