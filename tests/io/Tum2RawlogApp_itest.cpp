/* tum2rawlog end to end: the executable on a small temporary TUM folder and on
 * the shared fr1/rpy sequence, checked with our reader and with MRPT's
 * rawlog-edit run from a different working directory (skipped when
 * rawlog-edit is not installed). */
#include <roislam/io/CFrameSource.h>
#include <roislam/io/CRawlogFrameSource.h>
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/testing/TestData.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "TumFolderFixture.h"

namespace fs = std::filesystem;
using namespace roislam::io;
using namespace roislam::iotest;

namespace
{
std::string tum2rawlog()
{
  return roislam::testing::binaryDir() + "/apps/tum2rawlog/tum2rawlog";
}

std::optional<std::string> findRawlogEdit()
{
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  std::string dir;
  while (std::getline(ss, dir, ':'))
    if (!dir.empty() && fs::exists(fs::path(dir) / "rawlog-edit"))
      return (fs::path(dir) / "rawlog-edit").string();
  return std::nullopt;
}

std::string slurp(const std::string& file)
{
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct TRun
{
  int exitCode = -1;
  std::string out;  // stdout + stderr
};

// Runs `command` in folder `cwd`, capturing both output streams.
TRun run(const std::string& cwd, const std::string& command, const std::string& logFile)
{
  const std::string full =
      "cd '" + cwd + "' && " + command + " > '" + logFile + "' 2>&1 </dev/null";
  const int rc = std::system(full.c_str());
  TRun r;
  r.exitCode = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = slurp(logFile);
  return r;
}

// "Overall number of objects : N" from rawlog-edit --info.
long objectsInInfo(const std::string& out)
{
  std::smatch m;
  if (std::regex_search(out, m, std::regex("Overall number of objects\\s*:\\s*([0-9]+)")))
    return std::stol(m[1]);
  return -1;
}
}  // namespace

TEST(Tum2RawlogApp, EndToEndOnSmallFolder)
{
  ASSERT_TRUE(fs::exists(tum2rawlog())) << tum2rawlog();
  const auto tmp = roislam::testing::makeTempDir("io_t2r_e2e");
  const auto dir =
      writeTumFolder(tmp, "seq", {1.0, 2.0, 3.0, 4.0, 5.0}, {1.01, 2.0, 3.3, 4.0, 4.99});
  writeCameraIni((fs::path(dir) / "camera.ini").string(), smallCamera());
  std::ofstream(fs::path(dir) / "groundtruth.txt") << "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n";
  fs::create_directories(tmp + "/out");
  fs::create_directories(tmp + "/elsewhere");

  // Relative paths are resolved against the working directory of the call.
  const auto r =
      run(tmp, "'" + tum2rawlog() + "' --input seq --output out/seq.rawlog", tmp + "/log.txt");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("4 observations, 1 colour frames skipped"), std::string::npos) << r.out;
  const auto rawlog = tmp + "/out/seq.rawlog";
  ASSERT_TRUE(fs::exists(rawlog));
  EXPECT_TRUE(fs::exists(tmp + "/out/seq.groundtruth.txt"));
  EXPECT_EQ(slurp(tmp + "/out/seq.groundtruth.txt"), slurp(dir + "/groundtruth.txt"));

  CRawlogFrameSource src(rawlog);
  EXPECT_EQ(src.size(), 4u);
  CTumFrameSource tum(dir, smallCamera());
  while (auto a = tum.next())
  {
    auto b = src.next();
    ASSERT_TRUE(b);
    EXPECT_EQ(cv::norm(a->rgb, b->rgb, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(a->depth, b->depth, cv::NORM_INF), 0.0);
  }

  // Bad input: exit code 1, one line "tum2rawlog: error: ...", no output.
  const auto bad =
      run(tmp, "'" + tum2rawlog() + "' --input seq --output out/bad.rawlog --camera fr1",
          tmp + "/log2.txt");
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.out.find("tum2rawlog: error: "), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("16x12"), std::string::npos) << bad.out;
  EXPECT_FALSE(fs::exists(tmp + "/out/bad.rawlog"));
  EXPECT_FALSE(fs::exists(tmp + "/out/bad_Images"));

  const auto rawlogEdit = findRawlogEdit();
  if (!rawlogEdit)
    GTEST_SKIP() << "rawlog-edit not installed; MRPT tool checks skipped";
  const auto info = run(
      tmp + "/elsewhere", "'" + *rawlogEdit + "' --info -i '" + rawlog + "'", tmp + "/log3.txt");
  ASSERT_EQ(info.exitCode, 0) << info.out;
  EXPECT_EQ(objectsInInfo(info.out), 4) << info.out;
  EXPECT_NE(info.out.find("RGBD"), std::string::npos) << info.out;

  // Needs the depth of every observation: run from another folder, too.
  const auto pc =
      run(tmp + "/elsewhere",
          "'" + *rawlogEdit + "' --generate-3d-pointclouds -i '" + rawlog + "' -o '" + tmp +
              "/elsewhere/pc.rawlog'",
          tmp + "/log4.txt");
  EXPECT_EQ(pc.exitCode, 0) << pc.out;
  EXPECT_NE(pc.out.find("Entries modified                  : 4"), std::string::npos) << pc.out;
  fs::remove_all(tmp);
}

TEST(Tum2RawlogApp, ColourTimeOffsetAppliesOnceThroughARawlog)
{
  const auto tmp = roislam::testing::makeTempDir("io_t2r_time");
  const auto dir = writeTumFolder(tmp, "seq", {1.0, 2.0, 3.0}, {1.01, 2.0, 2.99});
  TSensorDescription d;
  d.name = "late-stamps";
  d.colour = smallCamera();
  d.colour_time_offset_ms = -7;
  std::ofstream(fs::path(dir) / "camera.ini") << d.toIniText();

  // The folder: colour frames at their stamps minus 7 ms, depth at its own.
  auto folder = CFrameSource::open(dir);
  EXPECT_DOUBLE_EQ(folder->sensor().sensor.colour_time_offset_ms, -7);
  const std::vector<double> rgb{1.0, 2.0, 3.0}, depth{1.01, 2.0, 2.99};
  std::vector<double> taken;
  for (std::size_t i = 0; auto f = folder->next(); ++i)
  {
    EXPECT_NEAR(f->timestamp, rgb[i] - 0.007, 1e-9) << i;
    EXPECT_NEAR(f->depthTimestamp, depth[i], 1e-9) << i;
    taken.push_back(f->timestamp);
  }
  ASSERT_EQ(taken.size(), 3u);

  // The rawlog keeps the raw stamps and the description beside it, so the
  // offset applies once when it is read back; its one stamp per
  // observation stays the depth's too.
  fs::create_directories(tmp + "/out");
  const auto r =
      run(tmp, "'" + tum2rawlog() + "' --input seq --output out/seq.rawlog", tmp + "/log.txt");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(
      slurp(tmp + "/out/seq.camera.ini").find("colour_time_offset_ms = -7"), std::string::npos);
  auto rawlog = CFrameSource::open(tmp + "/out/seq.rawlog");
  EXPECT_DOUBLE_EQ(rawlog->sensor().sensor.colour_time_offset_ms, -7);
  for (std::size_t i = 0; auto f = rawlog->next(); ++i)
  {
    ASSERT_LT(i, taken.size());
    EXPECT_NEAR(f->timestamp, taken[i], 1e-6) << i;
    EXPECT_DOUBLE_EQ(f->depthTimestamp, f->timestamp) << i;
  }
  fs::remove_all(tmp);
}

TEST(Tum2RawlogApp, FramesAreTimedByTheirClockAlikeThroughARawlog)
{
  // 40 frames of a 30 Hz camera stamped as fr1's are: 36 / 32 / 32 ms apart.
  const auto tmp = roislam::testing::makeTempDir("io_t2r_clock");
  std::vector<double> stamps;
  for (int k = 0; k < 40; ++k)
    stamps.push_back(std::round((5.0 + k / 30.0 + 1.3e-3 * ((k % 3) - 1)) * 1e6) / 1e6);
  const auto dir = writeTumFolder(tmp, "seq", stamps, stamps);
  TSensorDescription d;
  d.name = "free-running";
  d.colour = smallCamera();
  std::ofstream(fs::path(dir) / "camera.ini") << d.toIniText();
  auto folder = CFrameSource::open(dir);
  std::vector<double> taken;
  while (auto f = folder->next())
    taken.push_back(f->timestamp);
  ASSERT_EQ(taken.size(), stamps.size());
  ASSERT_TRUE(folder->frameClock());
  EXPECT_EQ(folder->frameClock()->clocked, 36u);
  // The stamps' intervals are up to 2.6 ms off the period, the times' a
  // fifth of that once the clock has a third of a second of stamps.
  for (std::size_t k = 10; k < taken.size(); ++k)
    EXPECT_NEAR(taken[k] - taken[k - 1], 1.0 / 30, 5e-4) << k;

  fs::create_directories(tmp + "/out");
  const auto r =
      run(tmp, "'" + tum2rawlog() + "' --input seq --output out/seq.rawlog", tmp + "/log.txt");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  auto rawlog = CFrameSource::open(tmp + "/out/seq.rawlog");
  for (std::size_t i = 0; auto f = rawlog->next(); ++i)
  {
    ASSERT_LT(i, taken.size());
    EXPECT_NEAR(f->timestamp, taken[i], 1e-6) << i;
  }
  // A frame reached by seeking is timed as it is in order: the frames
  // skipped still set the clock.
  for (auto* source : {folder.get(), rawlog.get()})
  {
    source->seek(25);
    const auto f = source->next();
    ASSERT_TRUE(f);
    EXPECT_NEAR(f->timestamp, taken[25], 1e-6) << source->name();
  }

  // A camera whose stamps are its frames' times.
  d.name = "triggered";
  d.regular_frame_clock = false;
  std::ofstream(fs::path(dir) / "camera.ini") << d.toIniText();
  auto asStamped = CFrameSource::open(dir);
  EXPECT_FALSE(asStamped->frameClock());
  for (std::size_t i = 0; auto f = asStamped->next(); ++i)
    EXPECT_EQ(f->timestamp, stamps[i]) << i;
  fs::remove_all(tmp);
}

TEST(Tum2RawlogApp, SharedSequenceConvertsTo250Observations)
{
  ROISLAM_REQUIRE_SHARED_TUM(dir);
  const auto tmp = roislam::testing::makeTempDir("io_t2r_shared");
  const auto rawlog = tmp + "/fr1_rpy.rawlog";
  const auto r =
      run(tmp, "'" + tum2rawlog() + "' --input '" + dir + "' --output '" + rawlog + "'",
          tmp + "/log.txt");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("250 observations, 0 colour frames skipped"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(tmp + "/fr1_rpy.groundtruth.txt"));

  CRawlogFrameSource src(rawlog);
  EXPECT_EQ(src.size(), 250u);
  EXPECT_DOUBLE_EQ(src.camera().fx(), 517.306408);
  ASSERT_TRUE(src.groundTruthFile());
  // The first frames are identical to reading the folder directly.
  CTumFrameSource tum(dir, cameraPreset("fr1"));
  for (int k = 0; k < 5; ++k)
  {
    auto a = tum.next();
    auto b = src.next();
    ASSERT_TRUE(a && b);
    EXPECT_NEAR(a->timestamp, b->timestamp, 1e-6);
    EXPECT_EQ(cv::norm(a->rgb, b->rgb, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(a->depth, b->depth, cv::NORM_INF), 0.0);
  }

  const auto rawlogEdit = findRawlogEdit();
  if (!rawlogEdit)
    GTEST_SKIP() << "rawlog-edit not installed";
  const auto info = run("/", "'" + *rawlogEdit + "' --info -i '" + rawlog + "'", tmp + "/log2.txt");
  ASSERT_EQ(info.exitCode, 0) << info.out;
  EXPECT_EQ(objectsInInfo(info.out), 250) << info.out;
  fs::remove_all(tmp);
}
