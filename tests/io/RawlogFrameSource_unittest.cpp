/* Rawlog writing and reading: bit-exact round trip through tum2rawlog's
 * library class, the sensor-pose convention on a synthetic plane, foreign
 * rawlog variants (rangeUnits, sensory frames, unregistered depth) and bad
 * input. */
#include <mrpt/config/CConfigFile.h>
#include <mrpt/img/TStereoCamera.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/obs/T3DPointsProjectionParams.h>
#include <mrpt/poses/CPose3DQuat.h>
#include <mrpt/serialization/CArchive.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/CRawlogFrameSource.h>
#include <roislam/io/CRawlogWriter.h>
#include <roislam/io/CTum2RawlogApp.h>
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/ObservationConversion.h>
#include <roislam/testing/TestData.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "TumFolderFixture.h"

namespace fs = std::filesystem;
using mrpt::obs::CObservation3DRangeScan;
using namespace roislam::io;
using namespace roislam::iotest;

namespace
{
CTum2RawlogApp::TResult convert(const std::string& in, const std::string& out)
{
  CTum2RawlogApp::TOptions o;
  o.input = in;
  o.output = out;
  CTum2RawlogApp app(o);
  return app.run();
}
}  // namespace

TEST(RawlogFrameSource, RoundTripIsBitExact)
{
  const auto tmp = roislam::testing::makeTempDir("io_rawlog_rt");
  const auto dir = writeTumFolder(tmp, "seq", {1.0, 1.5, 2.0, 3.0}, {1.001, 1.499, 2.05, 3.01});
  writeCameraIni((fs::path(dir) / "camera.ini").string(), smallCamera());
  std::ofstream(fs::path(dir) / "groundtruth.txt") << "1.0 0 0 0 0 0 0 1\n";
  std::ofstream(fs::path(dir) / "accelerometer.txt") << "1.0 0 9.8 0\n";

  const auto out = tmp + "/out/seq.rawlog";
  fs::create_directories(tmp + "/out");
  const auto r = convert(dir, out);
  EXPECT_EQ(r.frames, 3u);
  EXPECT_EQ(r.skipped, 1u);  // rgb 2.0 has no depth within 0.02 s
  EXPECT_TRUE(fs::is_regular_file(out));
  EXPECT_TRUE(fs::is_directory(tmp + "/out/seq_Images"));
  ASSERT_TRUE(r.groundTruth);
  EXPECT_TRUE(fs::is_regular_file(tmp + "/out/seq.groundtruth.txt"));
  ASSERT_TRUE(r.accelerometer);
  EXPECT_TRUE(fs::is_regular_file(tmp + "/out/seq.accelerometer.txt"));
  // Only the final names remain (no temporary leftovers).
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(tmp + "/out"))
  {
    ++entries;
    EXPECT_EQ(e.path().string().find("partial"), std::string::npos) << e.path();
  }
  EXPECT_EQ(entries, 4u);

  CTumFrameSource tum(dir, smallCamera());
  CRawlogFrameSource raw(out);
  ASSERT_EQ(raw.size(), 3u);
  EXPECT_EQ(raw.skippedFrames(), 0u);
  EXPECT_EQ(raw.name(), "seq");
  ASSERT_TRUE(raw.groundTruthFile());
  EXPECT_EQ(*raw.groundTruthFile(), fs::absolute(tmp + "/out/seq.groundtruth.txt").string());
  ASSERT_TRUE(raw.accelerometerFile());
  EXPECT_EQ(*raw.accelerometerFile(), fs::absolute(tmp + "/out/seq.accelerometer.txt").string());
  ASSERT_TRUE(tum.accelerometerFile());
  EXPECT_DOUBLE_EQ(raw.camera().fx(), 20.0);
  EXPECT_DOUBLE_EQ(raw.camera().cy(), 5.5);

  for (int pass = 0; pass < 2; ++pass)
  {
    std::size_t n = 0;
    while (auto a = tum.next())
    {
      auto b = raw.next();
      ASSERT_TRUE(b);
      EXPECT_EQ(b->index, n);
      EXPECT_NEAR(b->timestamp, a->timestamp, 1e-6);
      EXPECT_EQ(b->rgb.type(), CV_8UC3);
      EXPECT_EQ(cv::norm(a->rgb, b->rgb, cv::NORM_INF), 0.0);
      ASSERT_EQ(b->depth.type(), CV_32FC1);
      // Depth: the raw 16-bit values survive exactly (compare in raw units).
      const cv::Mat rawDepth =
          CTumFrameSource::readDepthImage(tum.entries()[n].depthFile, smallCamera());
      for (int y = 0; y < rawDepth.rows; ++y)
        for (int x = 0; x < rawDepth.cols; ++x)
          ASSERT_EQ(std::lround(b->depth.at<float>(y, x) * 5000.0), rawDepth.at<uint16_t>(y, x));
      EXPECT_EQ(cv::norm(a->depth, b->depth, cv::NORM_INF), 0.0);
      EXPECT_DOUBLE_EQ(b->camera.fx(), 20.0);
      ++n;
    }
    EXPECT_EQ(n, 3u);
    EXPECT_FALSE(raw.next());
    tum.rewind();
    raw.rewind();
  }

  // Stored observation fields follow the documented convention.
  auto obs = raw.nextObservation();
  ASSERT_TRUE(obs);
  EXPECT_EQ(obs->sensorLabel, "RGBD");
  EXPECT_FLOAT_EQ(obs->rangeUnits, 1.0f / 5000);
  EXPECT_TRUE(obs->range_is_depth);
  EXPECT_TRUE(obs->doDepthAndIntensityCamerasCoincide());
  EXPECT_TRUE(obs->intensityImage.isExternallyStored());
  const auto stored = obs->intensityImage.getExternalStorageFile();
  EXPECT_EQ(stored.front(), '/');  // absolute, for rawlog-edit from any folder
  EXPECT_TRUE(fs::exists(stored));
  EXPECT_NEAR((obs->sensorPose - tumSensorPose()).norm(), 0.0, 1e-12);

  // Moving rawlog + _Images together still works for our reader.
  fs::rename(tmp + "/out", tmp + "/moved");
  CRawlogFrameSource moved(tmp + "/moved/seq.rawlog");
  auto f = moved.next();
  ASSERT_TRUE(f);
  EXPECT_EQ(cv::norm(f->rgb, colourImage(16, 12, 0), cv::NORM_INF), 0.0);

  // CFrameSource::open dispatches files to the rawlog reader.
  auto viaOpen = CFrameSource::open(tmp + "/moved/seq.rawlog");
  EXPECT_EQ(viaOpen->size(), 3u);
  fs::remove_all(tmp);
}

TEST(RawlogFrameSource, SensorPoseConventionUnprojectsPlane)
{
  // A fronto-parallel plane at Z = 1.7 m in the TUM optical frame, seen by the
  // fr1 pinhole. Distortion is dropped here: MRPT's unprojectInto undistorts
  // pixel rays with cameraParams.dist, which this convention test is not about.
  const auto tmp = roislam::testing::makeTempDir("io_plane");
  mrpt::img::TCamera cam = cameraPreset("fr1");
  cam.dist.fill(0);
  cam.distortion = mrpt::img::DistortionModel::none;
  const double Z = 1.7;
  cv::Mat raw(480, 640, CV_16UC1, cv::Scalar(static_cast<uint16_t>(std::lround(Z * 5000))));
  raw.at<uint16_t>(10, 10) = 0;  // one invalid pixel
  {
    // Through a rawlog file, so the stored sensorPose is what gets tested.
    auto written = observationFromRawDepth(raw, 1.0f / 5000, cam, 100.0);
    written->intensityImage = mrpt::img::CImage(colourImage(640, 480, 0), mrpt::img::DEEP_COPY);
    written->hasIntensityImage = true;
    CRawlogWriter w(tmp + "/plane.rawlog");
    w.write(*written);
    w.commit();
  }
  CRawlogFrameSource source(tmp + "/plane.rawlog");
  auto obs = source.nextObservation();
  ASSERT_TRUE(obs);

  // Robot frame = optical frame.
  mrpt::maps::CSimplePointsMap local;
  mrpt::obs::T3DPointsProjectionParams pp;
  pp.takeIntoAccountSensorPoseOnRobot = true;
  obs->unprojectInto(local, pp);
  ASSERT_EQ(local.size(), 640u * 480u - 1u);
  double maxErr = 0;
  for (std::size_t i = 0; i < local.size(); i += 97)
  {
    mrpt::math::TPoint3D p;
    local.getPoint(i, p);
    maxErr = std::max(maxErr, std::abs(p.z - Z));
    // Back-projection lands on a pixel centre of the image.
    const double u = cam.fx() * p.x / p.z + cam.cx(), v = cam.fy() * p.y / p.z + cam.cy();
    maxErr = std::max(maxErr, std::abs(u - std::round(u)) * p.z / cam.fx());
    maxErr = std::max(maxErr, std::abs(v - std::round(v)) * p.z / cam.fy());
  }
  EXPECT_LT(maxErr, 1e-3);
  // Pixel (0,0) is top-left: optical x < 0, y < 0.
  mrpt::math::TPoint3D p0;
  local.getPoint(0, p0);
  EXPECT_NEAR(p0.x, (0 - cam.cx()) * Z / cam.fx(), 1e-3);
  EXPECT_NEAR(p0.y, (0 - cam.cy()) * Z / cam.fy(), 1e-3);

  // World points with robotPoseInTheWorld = TUM camera pose.
  const mrpt::poses::CPose3D camPose(0.5, -0.2, 1.1, 0.3, -0.2, 0.1);
  pp.robotPoseInTheWorld = camPose;
  mrpt::maps::CSimplePointsMap world;
  obs->unprojectInto(world, pp);
  ASSERT_EQ(world.size(), local.size());
  double maxWorldErr = 0;
  for (std::size_t i = 0; i < world.size(); i += 97)
  {
    mrpt::math::TPoint3D pl, pw;
    local.getPoint(i, pl);
    world.getPoint(i, pw);
    const auto expected = camPose.composePoint(pl);
    maxWorldErr = std::max(maxWorldErr, (expected - pw).norm());
  }
  EXPECT_LT(maxWorldErr, 1e-3);
  fs::remove_all(tmp);
}

TEST(RawlogFrameSource, ForeignRawlogVariants)
{
  const auto tmp = roislam::testing::makeTempDir("io_rawlog_foreign");
  const auto cam = smallCamera();

  // (a) rawlog-grabber/OpenNI2 style: millimetre rangeUnits, embedded colour,
  // action/sensory-frame format, other label and a non-RGBD observation mixed in.
  {
    mrpt::io::CFileGZOutputStream out(tmp + "/mm.rawlog");
    auto arch = mrpt::serialization::archiveFrom(out);
    for (int k = 0; k < 3; ++k)
    {
      cv::Mat mm(12, 16, CV_16UC1, cv::Scalar(1234 + k));
      auto o = observationFromRawDepth(mm, 0.001f, cam, 10.0 + k);
      o->sensorLabel = "OPENNI2";
      o->intensityImage = mrpt::img::CImage(colourImage(16, 12, k), mrpt::img::DEEP_COPY);
      o->hasIntensityImage = true;
      mrpt::obs::CActionCollection acts;
      mrpt::obs::CSensoryFrame sf;
      sf.insert(o);
      arch << acts << sf;
    }
  }
  CRawlogFrameSource mm(tmp + "/mm.rawlog");
  EXPECT_EQ(mm.size(), 3u);
  EXPECT_FALSE(mm.groundTruthFile());
  EXPECT_FALSE(mm.accelerometerFile());
  for (int k = 0; k < 3; ++k)
  {
    auto f = mm.next();
    ASSERT_TRUE(f);
    EXPECT_FLOAT_EQ(f->depth.at<float>(3, 4), (1234 + k) * 0.001f);
    EXPECT_NEAR(f->timestamp, 10.0 + k, 1e-6);
    EXPECT_EQ(cv::norm(f->rgb, colourImage(16, 12, k), cv::NORM_INF), 0.0);
  }
  EXPECT_FALSE(mm.next());

  // (b) Ranges instead of depth, and a depth camera 10 cm to the right
  // of the colour camera: the reader converts and re-projects into colour.
  {
    mrpt::io::CFileGZOutputStream out(tmp + "/unreg.rawlog");
    auto arch = mrpt::serialization::archiveFrom(out);
    const double Z = 2.0;
    cv::Mat ranges(12, 16, CV_16UC1);
    for (int r = 0; r < 12; ++r)
      for (int c = 0; c < 16; ++c)
      {
        const double kx = (c - cam.cx()) / cam.fx(), ky = (r - cam.cy()) / cam.fy();
        ranges.at<uint16_t>(r, c) =
            static_cast<uint16_t>(std::lround(Z * std::sqrt(1 + kx * kx + ky * ky) * 10000));
      }
    auto o = observationFromRawDepth(ranges, 1e-4f, cam, 1.0);
    o->range_is_depth = false;
    // Colour camera 10 cm to the left of the depth camera: MRPT depth frame
    // +y is left; the rotation part keeps the "optical" axes convention.
    o->relativePoseIntensityWRTDepth =
        mrpt::poses::CPose3D(0, 0.1, 0, mrpt::DEG2RAD(-90.0), 0, mrpt::DEG2RAD(-90.0));
    o->intensityImage = mrpt::img::CImage(colourImage(16, 12, 0), mrpt::img::DEEP_COPY);
    o->hasIntensityImage = true;
    arch << *o;
  }
  CRawlogFrameSource unreg(tmp + "/unreg.rawlog");
  auto f = unreg.next();
  ASSERT_TRUE(f);
  // Shift = fx * baseline / Z = 20 * 0.1 / 2 = 1 px to the right in the
  // colour image; the plane stays at Z = 2 and colour column 0 sees nothing.
  for (int r = 0; r < 12; ++r)
  {
    EXPECT_EQ(f->depth.at<float>(r, 0), 0.0f) << "row " << r;
    for (int c = 1; c < 16; ++c)
      EXPECT_NEAR(f->depth.at<float>(r, c), 2.0, 2e-4) << r << "," << c;
  }

  // (c) Camera override from the CFrameSource::open spec.
  auto over = CFrameSource::open(tmp + "/mm.rawlog", "fr3");
  EXPECT_DOUBLE_EQ(over->camera().fx(), 535.4);
  expectError([&] { over->next(); }, "16x12");  // fr3 is 640x480

  // (d) Two RGB-D sensors need a label choice.
  {
    mrpt::io::CFileGZOutputStream out(tmp + "/two.rawlog");
    auto arch = mrpt::serialization::archiveFrom(out);
    for (const char* label : {"A", "B", "A"})
    {
      auto o = frameToObservation(TRGBDFrame{
          0, 1.0, 1.0, colourImage(16, 12, 0), cv::Mat(12, 16, CV_32FC1, cv::Scalar(1.0f)), cam,
          ""});
      o->sensorLabel = label;
      arch << *o;
    }
  }
  expectError([&] { CRawlogFrameSource s(tmp + "/two.rawlog"); }, "sensor_label");
  CRawlogFrameSource::TOptions onlyA;
  onlyA.sensorLabel = "A";
  EXPECT_EQ(CRawlogFrameSource(tmp + "/two.rawlog", onlyA).size(), 2u);
  fs::remove_all(tmp);
}

TEST(RawlogFrameSource, OpenNI2GrabberIniDescribesRegisteredDepth)
{
  // Rebuild the observation fields exactly as COpenNI2Sensor (MRPT 2.5.8)
  // derives them from config/rawlog-grabber-openni2.ini, section [RGBD].
  const auto ini = roislam::testing::sourceDir() + "/config/rawlog-grabber-openni2.ini";
  ASSERT_TRUE(fs::exists(ini));
  mrpt::config::CConfigFile cfg(ini);
  EXPECT_EQ(cfg.read_string("RGBD", "driver", ""), "COpenNI2Sensor");
  EXPECT_FALSE(cfg.read_bool("global", "use_sensoryframes", true));
  mrpt::img::TStereoCamera sc;
  sc.loadFromConfigFile("RGBD", cfg);
  const mrpt::poses::CPose3D twist(0, 0, 0, mrpt::DEG2RAD(-90.0), 0, mrpt::DEG2RAD(-90.0));

  const int w = cfg.read_int("RGBD", "width", 0), h = cfg.read_int("RGBD", "height", 0);
  ASSERT_EQ(w, 640);
  ASSERT_EQ(h, 480);
  auto o = observationFromRawDepth(
      cv::Mat(h, w, CV_16UC1, cv::Scalar(1500)), 0.001f, sc.rightCamera, 5.0);
  o->cameraParams = sc.leftCamera;
  o->cameraParamsIntensity = sc.rightCamera;
  o->relativePoseIntensityWRTDepth =
      twist + mrpt::poses::CPose3D(mrpt::poses::CPose3DQuat(sc.rightCameraPose));
  o->sensorLabel = cfg.read_string("RGBD", "sensorLabel", "");
  o->intensityImage = mrpt::img::CImage(colourImage(w, h, 3), mrpt::img::DEEP_COPY);
  o->hasIntensityImage = true;
  EXPECT_TRUE(o->doDepthAndIntensityCamerasCoincide());

  // The reader takes the registered depth pixel for pixel (no re-projection).
  const auto frame = observationToFrame(*o, "grabber");
  EXPECT_EQ(frame.depth.size(), cv::Size(640, 480));
  EXPECT_EQ(cv::countNonZero(frame.depth != 1.5f), 0);
  EXPECT_DOUBLE_EQ(frame.camera.fx(), 525.0);
  EXPECT_DOUBLE_EQ(frame.camera.cx(), 319.5);
}

TEST(RawlogFrameSource, BadInput)
{
  const auto tmp = roislam::testing::makeTempDir("io_rawlog_bad");
  expectError([&] { CRawlogFrameSource s(tmp + "/absent.rawlog"); }, "absent.rawlog");

  const auto dir = writeTumFolder(tmp, "seq", {1.0, 2.0, 3.0, 4.0}, {1.0, 2.0, 3.0, 4.0});
  writeCameraIni((fs::path(dir) / "camera.ini").string(), smallCamera());
  const auto good = tmp + "/good.rawlog";
  CTum2RawlogApp::TOptions o;
  o.input = dir;
  o.output = good;
  o.compressLevel = 0;  // uncompressed so truncation hits object data directly
  CTum2RawlogApp(o).run();
  ASSERT_EQ(CRawlogFrameSource(good).size(), 4u);

  // Truncated in the middle of the last object.
  const auto bytes = fs::file_size(good);
  fs::copy_file(good, tmp + "/trunc.rawlog");
  fs::resize_file(tmp + "/trunc.rawlog", bytes - 100);
  expectError([&] { CRawlogFrameSource s(tmp + "/trunc.rawlog"); }, "trunc.rawlog");

  // Garbage / text file.
  std::ofstream(tmp + "/text.rawlog") << "this is not a rawlog at all\n";
  expectError([&] { CRawlogFrameSource s(tmp + "/text.rawlog"); }, "text.rawlog");

  // Empty file: no frames.
  std::ofstream(tmp + "/empty.rawlog").close();
  expectError([&] { CRawlogFrameSource s(tmp + "/empty.rawlog"); }, "no CObservation3DRangeScan");

  // External colour image deleted after conversion: named when read.
  fs::remove(tmp + "/good_Images/2.000000.png");
  CRawlogFrameSource s(good);
  ASSERT_TRUE(s.next());
  expectError([&] { s.next(); }, "2.000000.png");
  fs::remove_all(tmp);
}

TEST(RawlogWriter, UnwritableOutputLeavesNothing)
{
  const auto tmp = roislam::testing::makeTempDir("io_writer");
  expectError([&] { CRawlogWriter w(tmp + "/no/such/dir/x.rawlog"); }, "no/such/dir/x.rawlog");
  {
    CRawlogWriter w(tmp + "/x.rawlog");
    auto obs = frameToObservation(TRGBDFrame{
        0, 1.0, 1.0, colourImage(16, 12, 0), cv::Mat(12, 16, CV_32FC1, cv::Scalar(1.0f)),
        smallCamera(), ""});
    w.write(*obs);
    // destroyed without commit(): an error path
  }
  EXPECT_TRUE(fs::is_empty(tmp));
  {
    CRawlogWriter w(tmp + "/x.rawlog");
    auto obs = frameToObservation(TRGBDFrame{
        0, 1.0, 1.0, colourImage(16, 12, 0), cv::Mat(12, 16, CV_32FC1, cv::Scalar(1.0f)),
        smallCamera(), ""});
    w.write(*obs);
    w.commit();
    EXPECT_EQ(w.count(), 1u);
  }
  CRawlogFrameSource r(tmp + "/x.rawlog");
  auto f = r.next();
  ASSERT_TRUE(f);
  EXPECT_FLOAT_EQ(f->depth.at<float>(5, 5), 1.0f);
  EXPECT_EQ(cv::norm(f->rgb, colourImage(16, 12, 0), cv::NORM_INF), 0.0);
  fs::remove_all(tmp);
}

TEST(Tum2RawlogApp, BadInputLeavesNoOutput)
{
  const auto tmp = roislam::testing::makeTempDir("io_t2r_bad");
  const auto dir = writeTumFolder(tmp, "seq", {1.0, 2.0, 3.0}, {1.0, 2.0, 3.0});
  writeCameraIni((fs::path(dir) / "camera.ini").string(), smallCamera());
  fs::create_directories(tmp + "/out");

  // A corrupt image in the middle: error names it, nothing is left in out/.
  {
    std::ofstream(fs::path(dir) / "depth/2.000000.png", std::ios::trunc) << "garbage";
  }
  expectError([&] { convert(dir, tmp + "/out/x.rawlog"); }, "depth/2.000000.png");
  EXPECT_TRUE(fs::is_empty(tmp + "/out"));

  // Wrong size for the requested intrinsics.
  CTum2RawlogApp::TOptions o;
  o.input = writeTumFolder(tmp, "seq2", {1.0}, {1.0});
  o.output = tmp + "/out/y.rawlog";
  o.camera = "fr1";
  expectError([&] { CTum2RawlogApp(o).run(); }, "image is 16x12");
  EXPECT_TRUE(fs::is_empty(tmp + "/out"));

  // Unwritable output folder.
  o.camera = "auto";
  writeCameraIni(o.input + "/camera.ini", smallCamera());
  o.output = tmp + "/missing-folder/y.rawlog";
  expectError([&] { CTum2RawlogApp(o).run(); }, "missing-folder/y.rawlog");
  fs::remove_all(tmp);
}
