/* cameraPreset() values and resolveCamera() rules. */
#include <mrpt/config/CConfigFile.h>
#include <mrpt/containers/yaml.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>

#include "TumFolderFixture.h"

namespace fs = std::filesystem;
using roislam::io::cameraPreset;
using roislam::io::resolveCamera;

TEST(CameraPresets, ExactValues)
{
  const auto fr1 = cameraPreset("fr1");
  EXPECT_EQ(fr1.ncols, 640u);
  EXPECT_EQ(fr1.nrows, 480u);
  EXPECT_DOUBLE_EQ(fr1.fx(), 517.306408);
  EXPECT_DOUBLE_EQ(fr1.fy(), 516.469215);
  EXPECT_DOUBLE_EQ(fr1.cx(), 318.643040);
  EXPECT_DOUBLE_EQ(fr1.cy(), 255.313989);
  EXPECT_DOUBLE_EQ(fr1.k1(), 0.262383);
  EXPECT_DOUBLE_EQ(fr1.k2(), -0.953104);
  EXPECT_DOUBLE_EQ(fr1.p1(), -0.005358);
  EXPECT_DOUBLE_EQ(fr1.p2(), 0.002628);
  EXPECT_DOUBLE_EQ(fr1.k3(), 1.163314);
  EXPECT_EQ(fr1.distortion, mrpt::img::DistortionModel::plumb_bob);

  const auto fr2 = cameraPreset("fr2");
  EXPECT_DOUBLE_EQ(fr2.fx(), 520.908620);
  EXPECT_DOUBLE_EQ(fr2.fy(), 521.007327);
  EXPECT_DOUBLE_EQ(fr2.cx(), 325.141442);
  EXPECT_DOUBLE_EQ(fr2.cy(), 249.701764);
  EXPECT_DOUBLE_EQ(fr2.k1(), 0.231222);
  EXPECT_DOUBLE_EQ(fr2.k2(), -0.784899);
  EXPECT_DOUBLE_EQ(fr2.p1(), -0.003257);
  EXPECT_DOUBLE_EQ(fr2.p2(), -0.000105);
  EXPECT_DOUBLE_EQ(fr2.k3(), 0.917205);

  const auto fr3 = cameraPreset("fr3");
  EXPECT_DOUBLE_EQ(fr3.fx(), 535.4);
  EXPECT_DOUBLE_EQ(fr3.fy(), 539.2);
  EXPECT_DOUBLE_EQ(fr3.cx(), 320.1);
  EXPECT_DOUBLE_EQ(fr3.cy(), 247.6);
  EXPECT_EQ(fr3.distortion, mrpt::img::DistortionModel::none);
  EXPECT_DOUBLE_EQ(fr3.k1(), 0.0);

  const auto ros = cameraPreset("ros");
  EXPECT_DOUBLE_EQ(ros.fx(), 525.0);
  EXPECT_DOUBLE_EQ(ros.fy(), 525.0);
  EXPECT_DOUBLE_EQ(ros.cx(), 319.5);
  EXPECT_DOUBLE_EQ(ros.cy(), 239.5);

  EXPECT_THROW(cameraPreset("fr4"), std::invalid_argument);
}

TEST(CameraPresets, ResolveAutoAndFiles)
{
  const auto tmp = roislam::testing::makeTempDir("io_cam");
  for (const auto* d :
       {"rgbd_dataset_freiburg1_xyz", "rgbd_dataset_freiburg2_desk",
        "rgbd_dataset_freiburg3_long_office", "mysequence"})
    fs::create_directories(fs::path(tmp) / d);
  EXPECT_DOUBLE_EQ(resolveCamera("auto", tmp + "/rgbd_dataset_freiburg1_xyz").fx(), 517.306408);
  EXPECT_DOUBLE_EQ(resolveCamera("auto", tmp + "/rgbd_dataset_freiburg2_desk/").fx(), 520.908620);
  EXPECT_DOUBLE_EQ(resolveCamera("auto", tmp + "/rgbd_dataset_freiburg3_long_office").fx(), 535.4);
  EXPECT_DOUBLE_EQ(resolveCamera("auto", tmp + "/mysequence").fx(), 525.0);
  EXPECT_DOUBLE_EQ(resolveCamera("fr3", tmp + "/rgbd_dataset_freiburg1_xyz").fx(), 535.4);

  // camera.ini (TCamera format) wins for auto even in a freiburg1 folder.
  auto cam = roislam::iotest::smallCamera(32, 24);
  cam.dist = {0.1, -0.2, 0.001, 0.002, 0.3, 0, 0, 0};
  cam.distortion = mrpt::img::DistortionModel::plumb_bob;
  roislam::iotest::writeCameraIni(tmp + "/rgbd_dataset_freiburg1_xyz/camera.ini", cam);
  const auto fromIni = resolveCamera("auto", tmp + "/rgbd_dataset_freiburg1_xyz");
  EXPECT_DOUBLE_EQ(fromIni.fx(), 20.0);
  EXPECT_DOUBLE_EQ(fromIni.fy(), 21.0);
  EXPECT_DOUBLE_EQ(fromIni.cx(), 7.5);
  EXPECT_DOUBLE_EQ(fromIni.cy(), 5.5);
  EXPECT_EQ(fromIni.ncols, 32u);
  EXPECT_EQ(fromIni.nrows, 24u);
  EXPECT_DOUBLE_EQ(fromIni.k1(), 0.1);
  EXPECT_DOUBLE_EQ(fromIni.k3(), 0.3);

  // A calibration file given by path.
  const auto calib = tmp + "/calib.ini";
  roislam::iotest::writeCameraIni(calib, cam);
  EXPECT_DOUBLE_EQ(resolveCamera(calib, tmp + "/mysequence").fx(), 20.0);

  // The pre-2.x MRPT layout (dist without distortion_model) keeps its
  // distortion; an explicit "none" is respected.
  const std::string plain =
      "[CAMERA_PARAMS]\nresolution = [640 480]\ncx = 318.6\ncy = 255.3\nfx = 517.3\n"
      "fy = 516.5\ndist = [0.262383 -0.953104 -0.005358 0.002628 1.163314]\n";
  std::ofstream(tmp + "/olddist.ini") << plain;
  const auto old = resolveCamera(tmp + "/olddist.ini", tmp);
  EXPECT_EQ(old.distortion, mrpt::img::DistortionModel::plumb_bob);
  EXPECT_DOUBLE_EQ(old.k1(), 0.262383);
  EXPECT_DOUBLE_EQ(old.k3(), 1.163314);
  EXPECT_DOUBLE_EQ(old.p2(), 0.002628);
  std::ofstream(tmp + "/nodist.ini") << plain << "distortion_model = none\n";
  EXPECT_EQ(resolveCamera(tmp + "/nodist.ini", tmp).distortion, mrpt::img::DistortionModel::none);

  // Bad calibration files name the file.
  for (const auto& [file, content] : std::vector<std::pair<std::string, std::string>>{
           {tmp + "/nosection.ini", "[OTHER]\nfx=1\n"},
           {tmp + "/nofx.ini", "[CAMERA_PARAMS]\nresolution=[640 480]\ncx=1\ncy=1\n"}})
  {
    std::ofstream(file) << content;
    try
    {
      resolveCamera(file, tmp);
      ADD_FAILURE() << "no exception for " << file;
    }
    catch (const std::runtime_error& e)
    {
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(resolveCamera(tmp + "/absent.ini", tmp), std::runtime_error);

  // camera.yaml (OpenCV/ROS calibration layout, TCamera::asYAML) for auto.
  {
    std::ofstream out(tmp + "/mysequence/camera.yaml");
    roislam::iotest::smallCamera(32, 24).asYAML().printAsYAML(out);
  }
  const auto fromYaml = resolveCamera("auto", tmp + "/mysequence");
  EXPECT_DOUBLE_EQ(fromYaml.fx(), 20.0);
  EXPECT_DOUBLE_EQ(fromYaml.cy(), 5.5);
  EXPECT_EQ(fromYaml.ncols, 32u);
  std::ofstream(tmp + "/broken.yaml") << "image_width: [\n";
  EXPECT_THROW(resolveCamera(tmp + "/broken.yaml", tmp), std::runtime_error);
  fs::remove_all(tmp);
}
