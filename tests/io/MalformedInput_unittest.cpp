/* One test per malformed input the frame sources and calibration readers
 * meet: truncated PNGs, truncated rawlogs (cut anywhere), rawlogs of the
 * wrong class or with zero-size images, broken camera ini / yaml files. Each
 * must be a one-line error naming the file (and line for text), never a
 * crash and never a shorter sequence. */
#include <gtest/gtest.h>
#include <mrpt/containers/yaml.h>
#include <mrpt/core/aligned_allocator.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/CRawlogFrameSource.h>
#include <roislam/io/CRawlogWriter.h>
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/ObservationConversion.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "TumFolderFixture.h"

namespace fs = std::filesystem;
using namespace roislam::io;
using namespace roislam::iotest;

namespace
{
/** The one-line message of fn's exception; fails when there is none. */
std::string errorOf(const std::function<void()>& fn)
{
  try
  {
    fn();
  }
  catch (const std::exception& e)
  {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
    return what;
  }
  ADD_FAILURE() << "no exception";
  return "";
}

/** Reads every frame of a source. */
std::size_t readAll(CFrameSource& s)
{
  std::size_t n = 0;
  while (s.next())
    ++n;
  return n;
}

void truncateFile(const fs::path& p, double keep)
{
  fs::resize_file(p, static_cast<std::uintmax_t>(fs::file_size(p) * keep));
}

TRGBDFrame smallFrame(int seed)
{
  TRGBDFrame f;
  f.timestamp = f.depthTimestamp = 1.0 + seed;
  f.rgb = colourImage(16, 12, seed);
  f.depth = cv::Mat(12, 16, CV_32FC1, cv::Scalar(1.5f));
  f.camera = smallCamera();
  return f;
}
}  // namespace

TEST(MalformedInput, TruncatedPngNamesTheImage)
{
  const auto tmp = roislam::testing::makeTempDir("io_trunc_png");
  const auto dir = writeTumFolder(tmp, "seq", {1.0, 2.0}, {1.0, 2.0}, 64, 48);
  const auto cam = smallCamera(64, 48);
  for (const char* file : {"rgb/2.000000.png", "depth/2.000000.png"})
  {
    const fs::path png = fs::path(dir) / file;
    const std::string backup = png.string() + ".bak";
    fs::copy_file(png, backup);
    truncateFile(png, 0.5);
    CTumFrameSource src(dir, cam);
    ASSERT_TRUE(src.next());
    const std::string e = errorOf([&] { src.next(); });
    EXPECT_NE(e.find(std::string(file) + ": cannot decode image"), std::string::npos) << e;
    fs::remove(png);
    fs::rename(backup, png);
  }
  // A zero-byte image is caught the same way.
  fs::resize_file(fs::path(dir) / "rgb/1.000000.png", 0);
  CTumFrameSource src(dir, cam);
  EXPECT_NE(errorOf([&] { src.next(); }).find("rgb/1.000000.png"), std::string::npos);
  fs::remove_all(tmp);
}

TEST(MalformedInput, TruncatedRawlogIsAnErrorWhereverItIsCut)
{
  const auto tmp = roislam::testing::makeTempDir("io_trunc_rawlog");
  const std::string good = tmp + "/good.rawlog";
  {
    CRawlogWriter w(good, 0);  // uncompressed: every cut lands in object data
    for (int i = 0; i < 3; ++i)
      w.write(*frameToObservation(smallFrame(i)));
    w.commit();
  }
  ASSERT_EQ(CRawlogFrameSource(good).size(), 3u);
  const auto bytes = fs::file_size(good);
  int cuts = 0;
  for (std::uintmax_t keep = 1; keep < bytes; keep += bytes / 37 + 1)
  {
    const std::string cut = tmp + "/cut.rawlog";
    fs::copy_file(good, cut, fs::copy_options::overwrite_existing);
    fs::resize_file(cut, keep);
    // Either the cut is detected at open, or (cut exactly between objects)
    // the source is a valid, shorter rawlog; never a crash or a silent loss
    // of a frame in the middle.
    try
    {
      CRawlogFrameSource s(cut);
      EXPECT_EQ(readAll(s), s.size());
      EXPECT_LT(s.size(), 3u);
    }
    catch (const std::runtime_error& e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find("cut.rawlog"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      ++cuts;
    }
  }
  EXPECT_GE(cuts, 30);
  fs::remove_all(tmp);
}

TEST(MalformedInput, RawlogOfTheWrongClassIsNamed)
{
  const auto tmp = roislam::testing::makeTempDir("io_wrong_class");
  const std::string file = tmp + "/scans2d.rawlog";
  {
    CRawlogWriter w(file);
    mrpt::obs::CObservation2DRangeScan scan;
    scan.resizeScan(10);
    w.write(scan);
    w.write(scan);
    w.commit();
  }
  EXPECT_NE(
      errorOf([&] { CRawlogFrameSource s(file); })
          .find("no CObservation3DRangeScan with range and intensity images"),
      std::string::npos);
  // A 3-D scan without a colour image is not an RGB-D frame either.
  {
    CRawlogWriter w(file);
    auto obs = frameToObservation(smallFrame(0));
    obs->hasIntensityImage = false;
    w.write(*obs);
    w.commit();
  }
  EXPECT_NE(
      errorOf([&] { CRawlogFrameSource s(file); }).find("no CObservation3DRangeScan"),
      std::string::npos);
  fs::remove_all(tmp);
}

TEST(MalformedInput, ZeroSizeImagesInARawlogAreNamed)
{
  const auto tmp = roislam::testing::makeTempDir("io_zero_size");
  const std::string file = tmp + "/zero.rawlog";
  {
    CRawlogWriter w(file);
    auto good = frameToObservation(smallFrame(0));
    w.write(*good);
    // Depth 0x0 with depth intrinsics for 0x0 (consistent, but no depth).
    auto noDepth = frameToObservation(smallFrame(1));
    noDepth->rangeImage_setSize(0, 0);
    noDepth->cameraParams.ncols = noDepth->cameraParams.nrows = 0;
    w.write(*noDepth);
    // Colour 0x0.
    auto noColour = frameToObservation(smallFrame(2));
    noColour->intensityImage = mrpt::img::CImage();
    w.write(*noColour);
    w.commit();
  }
  CRawlogFrameSource s(file);
  ASSERT_EQ(s.size(), 3u);
  ASSERT_TRUE(s.next());
  EXPECT_NE(errorOf([&] { s.next(); }).find("frame 1: empty range image (0x0)"), std::string::npos);
  EXPECT_NE(errorOf([&] { s.next(); }).find("frame 1"), std::string::npos);
  fs::remove_all(tmp);
}

TEST(MalformedInput, CameraIniGarbageAndDuplicatesNameTheLine)
{
  const auto tmp = roislam::testing::makeTempDir("io_cam_ini");
  const std::string ini = tmp + "/cam.ini";
  writeCameraIni(ini, smallCamera());
  EXPECT_DOUBLE_EQ(resolveCamera(ini, tmp).fx(), 20.0);
  std::ofstream(ini, std::ios::app) << "fx = 99\n";
  EXPECT_NE(errorOf([&] { resolveCamera(ini, tmp); }).find(ini + ":"), std::string::npos);
  EXPECT_NE(
      errorOf([&] { resolveCamera(ini, tmp); }).find("duplicate key 'fx'"), std::string::npos);
  writeCameraIni(ini, smallCamera());
  std::ofstream(ini, std::ios::app) << "focal length 20\n";
  EXPECT_NE(
      errorOf([&] { resolveCamera(ini, tmp); }).find("expected a comment, [section] or key"),
      std::string::npos);
  std::ofstream(ini) << "[CAMERA_PARAMS\nfx = 1\n";
  EXPECT_EQ(
      errorOf([&] { resolveCamera(ini, tmp); }),
      ini + ":1: malformed section header '[CAMERA_PARAMS'");
  fs::remove_all(tmp);
}

TEST(MalformedInput, CameraYamlDuplicatesAndGarbageNameTheLine)
{
  const auto tmp = roislam::testing::makeTempDir("io_cam_yaml");
  const std::string yaml = tmp + "/cam.yaml";
  {
    std::ofstream out(yaml);
    smallCamera(32, 24).asYAML().printAsYAML(out);
  }
  EXPECT_EQ(resolveCamera(yaml, tmp).ncols, 32u);
  // MRPT alone would take the last value (320).
  std::ofstream(yaml, std::ios::app) << "image_width: 320\n";
  EXPECT_NE(
      errorOf([&] { resolveCamera(yaml, tmp); }).find("duplicate key 'image_width'"),
      std::string::npos);
  // MRPT alone reports "non-existing map key `image_width`" here.
  {
    std::ofstream out(yaml);
    smallCamera(32, 24).asYAML().printAsYAML(out);
    out << "this is garbage\n";
  }
  const std::string e = errorOf([&] { resolveCamera(yaml, tmp); });
  EXPECT_EQ(e.rfind(yaml + ":", 0), 0u) << e;
  EXPECT_NE(e.find("expected 'key: value', got 'this is garbage'"), std::string::npos) << e;
  fs::remove_all(tmp);
}

TEST(MalformedInput, AbsurdSizesInARawlogAreAnErrorNotACrash)
{
  // MRPT 2.5.8's aligned allocator returned null for an impossible matrix
  // size and the vector wrote through it (MrptAlignedMalloc.cpp); now the
  // allocation throws and the reader names the file. Input found by
  // fuzz_rawlog (its oom-* inputs need a memory limit: fuzz_replay_rawlog).
  for (const char* name : {"absurd-matrix-size"})
  {
    const std::string file =
        roislam::testing::sourceDir() + "/tests/fuzz/regressions/rawlog/" + name;
    const std::string copy = roislam::testing::makeTempDir("io_absurd") + "/x.rawlog";
    fs::copy_file(file, copy);
    const std::string e = errorOf([&] { CRawlogFrameSource s(copy); });
    EXPECT_NE(e.find(copy + ": object "), std::string::npos) << e;
    EXPECT_NE(e.find("corrupt or truncated rawlog"), std::string::npos) << e;
    fs::remove_all(fs::path(copy).parent_path());
  }
  mrpt::aligned_allocator_cpp11<uint16_t> alloc;
  EXPECT_THROW(alloc.allocate(std::size_t(1) << 62), std::bad_alloc);
}
