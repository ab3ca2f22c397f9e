// TSensorDescription: every key round-trips through the ini, every bad value
// names its [section] key; the presets; resolveSensor()'s choices and reasons.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/TSensorDescription.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using roislam::io::TSensorDescription;

namespace
{
/** A description with every value away from its default. */
TSensorDescription unusual()
{
  TSensorDescription d;
  d.name = "test-cam";
  d.colour = roislam::io::cameraPreset("fr1");  // distorted
  d.colour.ncols = 320;
  d.colour.nrows = 240;
  d.depth = roislam::io::cameraPreset("ros");
  d.depth.setIntrinsicParamsFromValues(575.5, 576.25, 314.5, 235.25);
  d.depth_registered = false;
  d.depth_pose_in_colour = mrpt::poses::CPose3D::FromString("[-0.025 0.002 0.001 0.8 -0.5 0.3]");
  d.estimate_registration = true;
  d.depth_scale = 1000;
  d.rolling_shutter_ms = 12.5;
  d.rolling_shutter_bottom_to_top = true;
  d.frame_rate = 60;
  d.colour_time_offset_ms = -4.5;
  d.regular_frame_clock = false;
  d.common_pixel_sigma_px = 0.35;
  d.keypoint_sigma_px = 0.85;
  d.keypoint_time_sigma_ms = 7.5;
  auto& n = d.depth_noise;
  n.model = "disparity";
  n.a = 0.002;
  n.b = 0.003;
  n.z0 = 0.5;
  n.disparity_bf = 40.5;
  n.disparity_steps_per_px = 16;
  n.disparity_noise_steps = 0.25;
  n.lateral_sigma_px = 0.75;
  return d;
}

TSensorDescription reload(const std::string& ini)
{
  TSensorDescription d;
  d.loadFromConfigFile(mrpt::config::CConfigFileMemory(ini), "SensorDescription");
  return d;
}

void expectSameCamera(const mrpt::img::TCamera& a, const mrpt::img::TCamera& b)
{
  EXPECT_EQ(a.ncols, b.ncols);
  EXPECT_EQ(a.nrows, b.nrows);
  EXPECT_DOUBLE_EQ(a.fx(), b.fx());
  EXPECT_DOUBLE_EQ(a.fy(), b.fy());
  EXPECT_DOUBLE_EQ(a.cx(), b.cx());
  EXPECT_DOUBLE_EQ(a.cy(), b.cy());
  EXPECT_EQ(a.distortion, b.distortion);
  for (std::size_t i = 0; i < a.dist.size(); ++i)
    EXPECT_DOUBLE_EQ(a.dist[i], b.dist[i]) << i;
}

void expectSame(const TSensorDescription& a, const TSensorDescription& b)
{
  EXPECT_EQ(a.name, b.name);
  expectSameCamera(a.colour, b.colour);
  EXPECT_EQ(a.depth_registered, b.depth_registered);
  EXPECT_EQ(a.estimate_registration, b.estimate_registration);
  if (!a.depth_registered)
    expectSameCamera(a.depth, b.depth);
  EXPECT_LT(
      (a.depth_pose_in_colour.asVectorVal() - b.depth_pose_in_colour.asVectorVal()).norm(), 1e-12);
  EXPECT_DOUBLE_EQ(a.depth_scale, b.depth_scale);
  EXPECT_DOUBLE_EQ(a.rolling_shutter_ms, b.rolling_shutter_ms);
  EXPECT_EQ(a.rolling_shutter_bottom_to_top, b.rolling_shutter_bottom_to_top);
  EXPECT_DOUBLE_EQ(a.frame_rate, b.frame_rate);
  EXPECT_DOUBLE_EQ(a.colour_time_offset_ms, b.colour_time_offset_ms);
  EXPECT_EQ(a.regular_frame_clock, b.regular_frame_clock);
  EXPECT_DOUBLE_EQ(a.common_pixel_sigma_px, b.common_pixel_sigma_px);
  EXPECT_DOUBLE_EQ(a.keypoint_sigma_px, b.keypoint_sigma_px);
  EXPECT_DOUBLE_EQ(a.keypoint_time_sigma_ms, b.keypoint_time_sigma_ms);
  const auto &n = a.depth_noise, &m = b.depth_noise;
  EXPECT_EQ(n.model, m.model);
  EXPECT_DOUBLE_EQ(n.a, m.a);
  EXPECT_DOUBLE_EQ(n.b, m.b);
  EXPECT_DOUBLE_EQ(n.z0, m.z0);
  EXPECT_DOUBLE_EQ(n.disparity_bf, m.disparity_bf);
  EXPECT_DOUBLE_EQ(n.disparity_steps_per_px, m.disparity_steps_per_px);
  EXPECT_DOUBLE_EQ(n.disparity_noise_steps, m.disparity_noise_steps);
  EXPECT_DOUBLE_EQ(n.lateral_sigma_px, m.lateral_sigma_px);
}

std::string write(const fs::path& file, const std::string& text)
{
  std::ofstream(file) << text;
  return file.string();
}
}  // namespace

TEST(SensorDescription, EveryKeyRoundTrips)
{
  const TSensorDescription d = unusual();
  const std::string ini = d.toIniText();
  // Every documented key is written.
  for (const char* key :
       {"name",
        "depth_registered",
        "depth_pose_in_colour",
        "estimate_registration",
        "depth_scale",
        "rolling_shutter_ms",
        "rolling_shutter_direction",
        "frame_rate",
        "colour_time_offset_ms",
        "common_pixel_sigma_px",
        "keypoint_sigma_px",
        "keypoint_time_sigma_ms",
        "depth_noise_model",
        "depth_noise_a",
        "depth_noise_b",
        "depth_noise_z0",
        "disparity_bf",
        "disparity_steps_per_px",
        "disparity_noise_steps",
        "lateral_sigma_px"})
    EXPECT_NE(ini.find(std::string(key) + " "), std::string::npos) << key;
  EXPECT_NE(ini.find("[DEPTH_CAMERA_PARAMS]"), std::string::npos);
  const TSensorDescription back = reload(ini);
  expectSame(d, back);
  EXPECT_DOUBLE_EQ(back.signedReadoutMs(), -12.5);
  // Saved again, the same text.
  EXPECT_EQ(back.toIniText(), ini);
}

TEST(SensorDescription, PresetsRoundTripAndCarryTheReadout)
{
  for (const char* name : {"fr1", "fr2", "fr3", "ros"})
  {
    const TSensorDescription p = roislam::io::sensorPreset(name);
    expectSame(p, reload(p.toIniText()));
    EXPECT_EQ(p.name, name);
    EXPECT_TRUE(p.depth_registered);
    EXPECT_DOUBLE_EQ(p.depth_scale, 5000);
    EXPECT_DOUBLE_EQ(p.frame_rate, 30);
    EXPECT_DOUBLE_EQ(p.rolling_shutter_ms, std::string(name) == "ros" ? 0 : 25) << name;
    EXPECT_FALSE(p.rolling_shutter_bottom_to_top);
    // Measured on fr1 only (CameraPresets.cpp).
    EXPECT_DOUBLE_EQ(p.common_pixel_sigma_px, std::string(name) == "fr1" ? 0.6 : 0) << name;
    EXPECT_DOUBLE_EQ(p.colour_time_offset_ms, std::string(name) == "fr1" ? -7 : 0) << name;
    // Real cameras: the camera's share of each keypoint's noise.
    EXPECT_GT(p.keypoint_sigma_px, 0) << name;
    EXPECT_DOUBLE_EQ(p.keypoint_sigma_px, roislam::io::sensorPreset("fr1").keypoint_sigma_px);
    EXPECT_GT(p.keypoint_time_sigma_ms, 0) << name;
    EXPECT_DOUBLE_EQ(
        p.keypoint_time_sigma_ms, roislam::io::sensorPreset("fr1").keypoint_time_sigma_ms);
  }
  // 7-Scenes: a Kinect v1 whose depth is not registered, in millimetres.
  const TSensorDescription seven = roislam::io::sensorPreset("7scenes");
  expectSame(seven, reload(seven.toIniText()));
  EXPECT_FALSE(seven.depth_registered);
  EXPECT_TRUE(seven.estimate_registration);  // 7-Scenes never published its calibration
  EXPECT_FALSE(roislam::io::sensorPreset("fr1").estimate_registration);
  EXPECT_DOUBLE_EQ(seven.depth_scale, 1000);
  EXPECT_DOUBLE_EQ(seven.depth.fx(), 585);
  EXPECT_DOUBLE_EQ(seven.depth.fy(), 585);
  EXPECT_DOUBLE_EQ(seven.depth.cx(), 320);
  EXPECT_DOUBLE_EQ(seven.depth.cy(), 240);
  EXPECT_DOUBLE_EQ(seven.colour.fx(), 525);
  EXPECT_DOUBLE_EQ(seven.rolling_shutter_ms, 25);
  EXPECT_DOUBLE_EQ(seven.keypoint_sigma_px, roislam::io::sensorPreset("fr1").keypoint_sigma_px);
  // A rendered camera adds none.
  EXPECT_DOUBLE_EQ(roislam::io::sensorPreset("icl").keypoint_sigma_px, 0);
  EXPECT_DOUBLE_EQ(roislam::io::sensorPreset("icl").keypoint_time_sigma_ms, 0);
  EXPECT_THROW(roislam::io::sensorPreset("fr4"), std::invalid_argument);
}

TEST(SensorDescription, BadValuesNameSectionAndKey)
{
  const std::string good = unusual().toIniText();
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"name", ""},
      {"depth_registered", "perhaps"},
      {"estimate_registration", "maybe"},
      {"depth_pose_in_colour", "[1 2 3]"},
      {"depth_pose_in_colour", "nonsense"},
      {"depth_scale", "0"},
      {"depth_scale", "abc"},
      {"rolling_shutter_ms", "-1"},
      {"rolling_shutter_ms", "20"},  // longer than a 60 Hz frame
      {"rolling_shutter_direction", "sideways"},
      {"frame_rate", "0"},
      {"colour_time_offset_ms", "-20"},  // more than a 60 Hz frame
      {"colour_time_offset_ms", "17"},
      {"colour_time_offset_ms", "nan"},
      {"regular_frame_clock", "sometimes"},
      {"common_pixel_sigma_px", "-0.1"},
      {"common_pixel_sigma_px", "nan"},
      {"keypoint_sigma_px", "-0.5"},
      {"keypoint_sigma_px", "inf"},
      {"keypoint_time_sigma_ms", "-1"},
      {"keypoint_time_sigma_ms", "20"},  // longer than a 60 Hz frame
      {"keypoint_time_sigma_ms", "nan"},
      {"depth_noise_model", "gaussian"},
      {"depth_noise_a", "-0.1"},
      {"depth_noise_b", "-1"},
      {"depth_noise_z0", "-1"},
      {"disparity_bf", "0"},
      {"disparity_steps_per_px", "0"},
      {"disparity_noise_steps", "-1"},
      {"lateral_sigma_px", "-0.5"},
      {"no_such_key", "1"}};
  for (const auto& [key, value] : bad)
  {
    mrpt::config::CConfigFileMemory cfg(good);
    cfg.write("SensorDescription", key, value);
    TSensorDescription d;
    try
    {
      d.loadFromConfigFile(cfg, "SensorDescription");
      ADD_FAILURE() << key << " = '" << value << "' was accepted";
    }
    catch (const std::exception& e)
    {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("[SensorDescription]"), std::string::npos) << e.what();
    }
  }
  // The cameras: a bad colour camera, an unregistered sensor without depth camera.
  {
    mrpt::config::CConfigFileMemory cfg(good);
    cfg.write("CAMERA_PARAMS", "fx", "-3");
    TSensorDescription d;
    EXPECT_THROW(d.loadFromConfigFile(cfg, "SensorDescription"), std::exception);
  }
  {
    auto d = unusual();
    d.depth_registered = true;
    mrpt::config::CConfigFileMemory cfg(d.toIniText());
    cfg.write("SensorDescription", "depth_registered", "false");
    try
    {
      TSensorDescription e;
      e.loadFromConfigFile(cfg, "SensorDescription");
      ADD_FAILURE() << "an unregistered sensor without [DEPTH_CAMERA_PARAMS] was accepted";
    }
    catch (const std::exception& e)
    {
      EXPECT_NE(std::string(e.what()).find("DEPTH_CAMERA_PARAMS"), std::string::npos) << e.what();
    }
  }
}

TEST(SensorDescription, FilesNameThemselvesInErrors)
{
  const fs::path dir = roislam::testing::makeTempDir("sensor_files");
  auto text = unusual().toIniText();
  // A bad value in place (a second frame_rate would be a duplicate key,
  // refused by the strict reading before the description sees it).
  const auto at = text.find("\nframe_rate = ");
  ASSERT_NE(at, std::string::npos) << text;
  text = text.substr(0, at) + "\nframe_rate = -2" + text.substr(text.find('\n', at + 1));
  const auto file = write(dir / "bad.ini", text);
  try
  {
    roislam::io::loadSensorFile(file);
    ADD_FAILURE() << "accepted";
  }
  catch (const std::runtime_error& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(what.find("[SensorDescription] frame_rate"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  const auto twice =
      write(dir / "twice.ini", unusual().toIniText() + "\n[SensorDescription]\nframe_rate = 30\n");
  try
  {
    roislam::io::loadSensorFile(twice);
    ADD_FAILURE() << "accepted a duplicate key";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find(twice + ":"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("duplicate key 'frame_rate'"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(roislam::io::loadSensorFile((dir / "absent.ini").string()), std::runtime_error);
  // A plain TCamera ini is a registered, global-shutter description named after the file.
  const auto plain = write(
      dir / "mycam.ini",
      "[CAMERA_PARAMS]\nresolution = [640 480]\ncx = 320\ncy = 240\nfx = 500\nfy = 501\n"
      "dist = [0 0 0 0 0]\n");
  const auto d = roislam::io::loadSensorFile(plain);
  EXPECT_EQ(d.name, "mycam");
  EXPECT_DOUBLE_EQ(d.colour.fy(), 501);
  EXPECT_TRUE(d.depth_registered);
  EXPECT_DOUBLE_EQ(d.rolling_shutter_ms, 0);
  fs::remove_all(dir);
}

TEST(SensorDescription, ResolveSaysWhatItPickedAndWhy)
{
  const fs::path dir = roislam::testing::makeTempDir("sensor_resolve");
  const fs::path fr1 = dir / "rgbd_dataset_freiburg1_xyz", other = dir / "mysequence",
                 own = dir / "withcamera";
  for (const auto& p : {fr1, other, own})
    fs::create_directories(p);
  write(own / "camera.ini", unusual().toIniText());

  const auto a = roislam::io::resolveSensor("auto", fr1.string());
  EXPECT_EQ(a.source, "preset fr1");
  EXPECT_NE(a.reason.find("freiburg1"), std::string::npos) << a.reason;
  EXPECT_DOUBLE_EQ(a.sensor.rolling_shutter_ms, 25);
  // The colour images' time is said where the camera is described.
  EXPECT_NE(a.summary().find("colour images taken 7 ms before their stamps"), std::string::npos)
      << a.summary();
  EXPECT_DOUBLE_EQ(a.toJson()["colour_time_offset_ms"].get<double>(), -7);

  const auto b = roislam::io::resolveSensor("auto", other.string());
  EXPECT_EQ(b.source, "preset ros");
  EXPECT_NE(b.reason.find("ROS defaults"), std::string::npos) << b.reason;
  EXPECT_NE(b.summary().find("ROS defaults"), std::string::npos) << b.summary();
  EXPECT_DOUBLE_EQ(b.sensor.rolling_shutter_ms, 0);
  EXPECT_EQ(b.summary().find("colour images taken"), std::string::npos) << b.summary();

  const auto c = roislam::io::resolveSensor("auto", own.string());
  EXPECT_EQ(c.source, "file " + (own / "camera.ini").string());
  EXPECT_NE(c.reason.find("camera.ini"), std::string::npos);
  expectSame(c.sensor, unusual());
  const auto j = c.toJson();
  EXPECT_EQ(j["name"], "test-cam");
  EXPECT_EQ(j["source"], c.source);
  EXPECT_DOUBLE_EQ(j["rolling_shutter_ms"].get<double>(), -12.5);
  // A camera whose stamps are its frames' times says so.
  EXPECT_FALSE(j["regular_frame_clock"].get<bool>());
  EXPECT_NE(c.summary().find("frames timed by their stamps"), std::string::npos) << c.summary();
  EXPECT_TRUE(a.toJson()["regular_frame_clock"].get<bool>());
  EXPECT_EQ(a.summary().find("frames timed by their stamps"), std::string::npos) << a.summary();

  const auto d = roislam::io::resolveSensor("fr3", fr1.string());
  EXPECT_EQ(d.source, "preset fr3");
  EXPECT_EQ(d.reason, "--camera fr3");

  // A recording's description travels beside it as <stem>.camera.ini.
  const fs::path rec = dir / "room.oni";
  write(rec, "");
  EXPECT_FALSE(roislam::io::resolveSensorForFile("auto", rec.string()));
  write(dir / "room.camera.ini", unusual().toIniText());
  const auto e = roislam::io::resolveSensorForFile("auto", rec.string());
  ASSERT_TRUE(e);
  EXPECT_NE(e->reason.find("room.camera.ini"), std::string::npos) << e->reason;
  EXPECT_EQ(roislam::io::resolveSensorForFile("fr2", rec.string())->source, "preset fr2");
  fs::remove_all(dir);
}
