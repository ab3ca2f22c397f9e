// io::loadTumTrajectory / saveTumTrajectory (implemented with the evaluation
// work; the file format is what the benchmark scripts read).
#include <gtest/gtest.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/testing/TestData.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace
{
namespace fs = std::filesystem;

std::string writeFile(const std::string& dir, const std::string& name, const std::string& text)
{
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string loadError(const std::string& path)
{
  try
  {
    roislam::io::loadTumTrajectory(path);
  }
  catch (const std::runtime_error& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(TumTrajectory, ParsesSeparatorsCommentsAndSkipsLikeTheScripts)
{
  const auto dir = roislam::testing::makeTempDir("eval_tumtraj");
  const auto path = writeFile(
      dir, "t.txt",
      "# ground truth trajectory\n"
      "\n"
      "3.0 1 2 3 0 0 0 1\n"
      "1.0,4,5,6,0,0,0,2\n"         // commas, non-unit quaternion
      "2.0\t7\t8\t9\t0\t0\t1\t1\n"  // tabs, 90 deg about z (unnormalised)
      "  # indented comment\n"
      "4.0 nan 0 0 0 0 0 1\n"  // NaN: skipped
      "5.0 1 1 1 0 0 0 0\n"    // all-zero quaternion: skipped
      "6.0 1 1 1 0 0 0 -0\n"   // -0 is zero too
      "0.5 +1 -2 3e-1 0 0 0 1\r\n");
  const auto t = roislam::io::loadTumTrajectory(path, roislam::io::EInvalidPose::Skip);
  ASSERT_EQ(t.size(), 4u);
  // Sorted by stamp.
  EXPECT_DOUBLE_EQ(t[0].timestamp, 0.5);
  EXPECT_DOUBLE_EQ(t[1].timestamp, 1.0);
  EXPECT_DOUBLE_EQ(t[2].timestamp, 2.0);
  EXPECT_DOUBLE_EQ(t[3].timestamp, 3.0);
  EXPECT_DOUBLE_EQ(t[0].pose.x(), 1.0);
  EXPECT_DOUBLE_EQ(t[0].pose.y(), -2.0);
  EXPECT_DOUBLE_EQ(t[0].pose.z(), 0.3);
  EXPECT_DOUBLE_EQ(t[1].pose.z(), 6.0);
  // Quaternions are normalised: (0,0,0,2) is the identity, (0,0,1,1) a 90 deg yaw.
  EXPECT_NEAR(t[1].pose.yaw(), 0.0, 1e-15);
  EXPECT_NEAR(t[2].pose.yaw(), M_PI / 2, 1e-15);
  const auto R = t[2].pose.getRotationMatrix();
  EXPECT_NEAR(R(0, 1), -1.0, 1e-15);
  EXPECT_NEAR(R(1, 0), 1.0, 1e-15);
  fs::remove_all(dir);
}

TEST(TumTrajectory, MalformedLinesNameFileAndLine)
{
  const auto dir = roislam::testing::makeTempDir("eval_tumtraj_bad");
  const auto few = writeFile(dir, "few.txt", "# c\n1 2 3 4 0 0 0 1\n2 3 4 5 0 0 1\n");
  EXPECT_EQ(
      loadError(few), few + ":3: expected 8 values (timestamp tx ty tz qx qy qz qw), found 7");
  const auto word = writeFile(dir, "word.txt", "1 2 3 4 0 0 0 1\n2 3 abc 5 0 0 0 1\n");
  EXPECT_EQ(loadError(word), word + ":2: not a number: 'abc'");
  const auto inf = writeFile(dir, "inf.txt", "1 inf 3 4 0 0 0 1\n");
  EXPECT_NE(loadError(inf).find(inf + ":1:"), std::string::npos);
  EXPECT_EQ(loadError(dir + "/missing.txt"), dir + "/missing.txt: cannot open");
  fs::remove_all(dir);
}

TEST(TumTrajectory, SaveLoadRoundTripIsExact)
{
  const auto dir = roislam::testing::makeTempDir("eval_tumtraj_rt");
  roislam::io::TTrajectory t;
  for (int k = 0; k < 50; ++k)
  {
    roislam::io::TPoseStamped p;
    p.timestamp = 1305031102.175304 + k / 30.0;
    p.pose = mrpt::poses::CPose3D(0.1 * k, -0.37 * k, 1.0 / 3.0, 0.05 * k, -0.4 + 0.01 * k, 2.9);
    t.push_back(p);
  }
  const std::string file = dir + "/rt.txt";
  roislam::io::saveTumTrajectory(file, t, "two\nline header");
  // Nothing but the final file remains (written through a temporary name).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "# two");
  int dataLines = 0;
  while (std::getline(in, line))
  {
    if (line[0] == '#')
      continue;
    ++dataLines;
    const double qw = std::stod(line.substr(line.rfind(' ') + 1));
    EXPECT_GE(qw, 0.0) << line;  // written with qw >= 0
  }
  EXPECT_EQ(dataLines, 50);
  const auto back = roislam::io::loadTumTrajectory(file);
  ASSERT_EQ(back.size(), t.size());
  for (std::size_t k = 0; k < t.size(); ++k)
  {
    EXPECT_EQ(back[k].timestamp, t[k].timestamp);  // shortest round-trip text: exact
    EXPECT_EQ(back[k].pose.x(), t[k].pose.x());
    EXPECT_LT((back[k].pose.getRotationMatrix() - t[k].pose.getRotationMatrix()).norm(), 1e-14);
  }
  EXPECT_THROW(roislam::io::saveTumTrajectory(dir + "/no/such/dir/x.txt", t), std::runtime_error);
  fs::remove_all(dir);
}

TEST(TumTrajectory, NanOrZeroQuaternionInGroundTruthIsAnErrorUnlessSkipped)
{
  const auto dir = roislam::testing::makeTempDir("eval_tumtraj_invalid");
  const auto nan = writeFile(dir, "nan.txt", "1 0 0 0 0 0 0 1\n2 nan 0 0 0 0 0 1\n");
  EXPECT_EQ(
      loadError(nan), nan +
                          ":2: NaN value (roi-eval --skip-invalid skips such lines as the "
                          "benchmark scripts do)");
  const auto zero = writeFile(dir, "zero.txt", "# gt\n1 0 0 0 0 0 0 1\n\n2 1 2 3 0 0 0 0\n");
  EXPECT_EQ(loadError(zero).rfind(zero + ":4: zero quaternion (no rotation)", 0), 0u)
      << loadError(zero);
  const auto tiny = writeFile(dir, "tiny.txt", "2 1 2 3 0 0 1e-9 0\n");
  EXPECT_EQ(loadError(tiny).rfind(tiny + ":1: zero quaternion", 0), 0u) << loadError(tiny);
  // The scripts' semantics on request: the lines are dropped.
  using roislam::io::EInvalidPose;
  EXPECT_EQ(roislam::io::loadTumTrajectory(nan, EInvalidPose::Skip).size(), 1u);
  EXPECT_EQ(roislam::io::loadTumTrajectory(zero, EInvalidPose::Skip).size(), 1u);
  fs::remove_all(dir);
}
