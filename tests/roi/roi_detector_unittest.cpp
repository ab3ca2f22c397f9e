#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/roi/CRoiDetector.h>
#include <roislam/testing/TestData.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <sstream>

using roislam::roi::CRoiDetector;

namespace
{
// A uniform grey image with one "printed text" patch of strong detail.
cv::Mat imageWithDetailPatch(const cv::Rect& patch, unsigned seed = 1)
{
  cv::Mat img(480, 640, CV_8UC1, cv::Scalar(128));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> cx(patch.x, patch.x + patch.width - 12);
  std::uniform_int_distribution<int> cy(patch.y, patch.y + patch.height - 12);
  cv::rectangle(img, patch, cv::Scalar(255), cv::FILLED);
  for (int i = 0; i < patch.area() / 60; ++i)
  {
    const cv::Point p(cx(rng), cy(rng));
    cv::rectangle(img, cv::Rect(p, cv::Size(6 + (i % 5), 8)), cv::Scalar(0), cv::FILLED);
  }
  return img;
}

double iou(const cv::Rect& a, const cv::Rect& b)
{
  return static_cast<double>((a & b).area()) / static_cast<double>((a | b).area());
}

CRoiDetector detectorFor(const std::string& preset)
{
  CRoiDetector::TOptions o;
  o.setPreset(preset);
  return CRoiDetector(o);
}
}  // namespace

TEST(CRoiDetector, findsHighDetailPatch)
{
  const cv::Rect patch(300, 150, 200, 140);
  const cv::Mat img = imageWithDetailPatch(patch);
  for (const std::string preset : {"small", "big"})
  {
    const auto roi = detectorFor(preset).detect(img);
    ASSERT_TRUE(roi.has_value()) << preset;
    EXPECT_GE(iou(roi->box, patch), 0.7) << preset << " box " << roi->box;
  }
}

TEST(CRoiDetector, noRoiOnBlankImage)
{
  const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(200));
  EXPECT_FALSE(detectorFor("small").detect(blank).has_value());
  EXPECT_FALSE(detectorFor("big").detect(blank).has_value());
  // A smooth gradient has no edges above Canny's 250/300 thresholds either.
  cv::Mat ramp(480, 640, CV_8UC1);
  for (int r = 0; r < ramp.rows; ++r)
    ramp.row(r).setTo(cv::Scalar(r * 255 / ramp.rows));
  EXPECT_FALSE(detectorFor("big").detect(ramp).has_value());
}

TEST(CRoiDetector, acceptsColourImages)
{
  const cv::Rect patch(100, 100, 160, 120);
  cv::Mat bgr;
  cv::cvtColor(imageWithDetailPatch(patch), bgr, cv::COLOR_GRAY2BGR);
  const auto roi = detectorFor("big").detect(bgr);
  ASSERT_TRUE(roi.has_value());
  EXPECT_GE(iou(roi->box, patch), 0.7);
}

TEST(CRoiDetector, bigPresetGivesBiggerRoiThanSmall)
{
  // Two detail patches separated by a small gap: "big" merges them.
  cv::Mat img = imageWithDetailPatch(cv::Rect(100, 100, 150, 150), 3);
  const cv::Mat other = imageWithDetailPatch(cv::Rect(256, 100, 150, 150), 4);
  other(cv::Rect(256, 100, 150, 150)).copyTo(img(cv::Rect(256, 100, 150, 150)));
  const auto small = detectorFor("small").detect(img);
  const auto big = detectorFor("big").detect(img);
  ASSERT_TRUE(small && big);
  EXPECT_GT(big->box.area(), small->box.area());
}

TEST(CRoiDetector, bigPresetGivesBiggerRoisOnRealFrames)
{
  ROISLAM_REQUIRE_SHARED_TUM(dir);
  std::ifstream f(dir + "/rgb.txt");
  std::string line;
  std::vector<std::string> files;
  while (std::getline(f, line))
  {
    if (line.empty() || line[0] == '#')
      continue;
    std::istringstream ss(line);
    double t;
    std::string name;
    ss >> t >> name;
    files.push_back(dir + "/" + name);
  }
  ASSERT_EQ(files.size(), 250u);
  double small = 0, big = 0;
  int nSmall = 0, nBig = 0;
  for (std::size_t i = 0; i < files.size(); i += 10)
  {
    const cv::Mat img = cv::imread(files[i], cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(img.empty()) << files[i];
    if (auto r = detectorFor("small").detect(img))
      small += r->box.area(), ++nSmall;
    if (auto r = detectorFor("big").detect(img))
      big += r->box.area(), ++nBig;
  }
  ASSERT_GT(nSmall, 0);
  ASSERT_GT(nBig, 0);
  // Measured: small ~4 % of the image, big ~18 %.
  EXPECT_GT(big / nBig, 2.0 * small / nSmall);
}

TEST(CRoiDetectorOptions, iniErrorsNameSectionAndKey)
{
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("RoiDetector", "preset", "huge");
  CRoiDetector::TOptions o;
  try
  {
    o.loadFromConfigFile(cfg, "RoiDetector");
    FAIL() << "expected an exception";
  }
  catch (const std::exception& e)
  {
    EXPECT_NE(std::string(e.what()).find("[RoiDetector] preset"), std::string::npos) << e.what();
  }
  mrpt::config::CConfigFileMemory cfg2;
  cfg2.write("RoiDetector", "preset", "custom");
  cfg2.write("RoiDetector", "dilations", -1);
  EXPECT_THROW(o.loadFromConfigFile(cfg2, "RoiDetector"), std::invalid_argument);
}

TEST(CRoiDetectorOptions, roundTripThroughIni)
{
  CRoiDetector::TOptions a;
  a.setPreset("custom");
  a.erosions = 3;
  a.dilations = 4;
  a.canny_low = 100;
  mrpt::config::CConfigFileMemory cfg;
  a.saveToConfigFile(cfg, "RoiDetector");
  CRoiDetector::TOptions b;
  b.loadFromConfigFile(cfg, "RoiDetector");
  EXPECT_EQ(b.preset, "custom");
  EXPECT_EQ(b.erosions, 3);
  EXPECT_EQ(b.dilations, 4);
  EXPECT_DOUBLE_EQ(b.canny_low, 100);
}
