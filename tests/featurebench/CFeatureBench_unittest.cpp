/* Unit tests of CFeatureBench: options, homographies, frame selection, and a
 * small run on a generated TUM-like folder (no shared data needed). */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/featurebench/CFeatureBench.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

using roislam::featurebench::CFeatureBench;

namespace
{
/** A TUM-like folder with n textured 640x480 frames. */
std::string makeSequence(int n)
{
  const std::string dir = roislam::testing::makeTempDir("featurebench");
  std::filesystem::create_directories(dir + "/rgb");
  std::ofstream list(dir + "/rgb.txt");
  list << "# color images\n# timestamp filename\n";
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> ux(0, 639), uy(0, 479), ur(3, 25), uv(0, 255);
  for (int f = 0; f < n; ++f)
  {
    cv::Mat img(480, 640, CV_8UC3, cv::Scalar(128, 128, 128));
    for (int k = 0; k < 400; ++k)
    {
      const cv::Point c(ux(rng), uy(rng));
      std::vector<cv::Point> poly;
      const int r = ur(rng);
      for (int v = 0; v < 3 + k % 3; ++v)
        poly.emplace_back(c.x + (uv(rng) - 128) * r / 100, c.y + (uv(rng) - 128) * r / 100);
      cv::fillConvexPoly(img, poly, cv::Scalar(uv(rng), uv(rng), uv(rng)), cv::LINE_AA);
    }
    cv::GaussianBlur(img, img, cv::Size(0, 0), 1.0);
    const std::string name = "rgb/" + std::to_string(f) + ".png";
    cv::imwrite(dir + "/" + name, img);
    list << 100.0 + f * 0.033 << " " << name << "\n";
  }
  return dir;
}
}  // namespace

TEST(CFeatureBench, OptionsValidationNamesTheKey)
{
  CFeatureBench::TOptions o;
  try
  {
    CFeatureBench b(o);
    FAIL() << "missing input accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("input"), std::string::npos) << e.what();
  }
  o.input = "/nonexistent";
  o.extractors = {"sift", "brisk"};
  try
  {
    CFeatureBench b(o);
    FAIL() << "unknown extractor accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("extractors"), std::string::npos) << e.what();
  }
  o.extractors = {"surf"};
  o.frames = 0;
  EXPECT_THROW(CFeatureBench{o}, std::invalid_argument);
}

TEST(CFeatureBench, IniRoundTrip)
{
  CFeatureBench::TOptions o;
  o.input = "/some/dir";
  o.frames = 7;
  o.max_features = 300;
  o.extractors = {"surf", "orb"};
  o.transforms = {"rot30", "blur"};
  mrpt::config::CConfigFileMemory cfg;
  o.saveToConfigFile(cfg, "FeatureBench");
  CFeatureBench::TOptions p;
  p.loadFromConfigFile(cfg, "FeatureBench");
  EXPECT_EQ(p.input, o.input);
  EXPECT_EQ(p.frames, 7);
  EXPECT_EQ(p.max_features, 300);
  EXPECT_EQ(p.extractors, o.extractors);
  EXPECT_EQ(p.transforms, o.transforms);
  cfg.write("FeatureBench", "max_features", -3);
  EXPECT_THROW(p.loadFromConfigFile(cfg, "FeatureBench"), std::invalid_argument);
}

TEST(CFeatureBench, Homographies)
{
  const cv::Size sz(640, 480);
  const cv::Matx33d R = CFeatureBench::homography("rot30", sz);
  // The image centre is fixed; a point 100 px right of it turns by 30 degrees.
  const cv::Vec3d c = R * cv::Vec3d(319.5, 239.5, 1), p = R * cv::Vec3d(419.5, 239.5, 1);
  EXPECT_NEAR(c[0], 319.5, 1e-9);
  EXPECT_NEAR(c[1], 239.5, 1e-9);
  EXPECT_NEAR(std::hypot(p[0] - 319.5, p[1] - 239.5), 100.0, 1e-9);
  EXPECT_NEAR(std::abs(std::atan2(p[1] - 239.5, p[0] - 319.5)) * 180 / CV_PI, 30.0, 1e-9);
  const cv::Matx33d S = CFeatureBench::homography("scale2.0", sz);
  EXPECT_NEAR(S(0, 0), 2.0, 1e-12);
  EXPECT_EQ(CFeatureBench::homography("blur", sz), cv::Matx33d::eye());
  EXPECT_THROW(CFeatureBench::homography("shear", sz), std::invalid_argument);
}

TEST(CFeatureBench, SelectFramesEvenlyAndReportsBadLines)
{
  const std::string dir = roislam::testing::makeTempDir("featurebench_list");
  {
    std::ofstream f(dir + "/rgb.txt");
    f << "# comment\n";
    for (int i = 0; i < 10; ++i)
      f << i << ".0 rgb/" << i << ".png\n";
  }
  const auto sel = CFeatureBench::selectFrames(dir, 3);
  ASSERT_EQ(sel.size(), 3u);
  EXPECT_EQ(sel[0], dir + "/rgb/0.png");
  EXPECT_EQ(sel[2], dir + "/rgb/9.png");
  EXPECT_EQ(CFeatureBench::selectFrames(dir, 50).size(), 10u);
  {
    std::ofstream f(dir + "/rgb.txt", std::ios::app);
    f << "garbage\n";
  }
  try
  {
    CFeatureBench::selectFrames(dir, 3);
    FAIL() << "malformed line accepted";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("rgb.txt:12"), std::string::npos) << e.what();
  }
  EXPECT_THROW(CFeatureBench::selectFrames(dir + "/missing", 3), std::runtime_error);
}

TEST(CFeatureBench, RunsOnGeneratedFramesWithSaneResults)
{
  CFeatureBench::TOptions o;
  o.input = makeSequence(2);
  o.frames = 2;
  o.extractors = {"surf", "orb"};
  o.transforms = {"rot30", "scale1.5", "brightness"};
  const auto res = CFeatureBench(o).run();
  EXPECT_EQ(res.frames, 2u);
  EXPECT_EQ(res.imageSize, cv::Size(640, 480));
  ASSERT_EQ(res.rows.size(), 2u * 4u);  // "none" + 3 transforms per extractor
  for (const std::string ex : {"surf", "orb"})
  {
    const auto* none = res.find(ex, "none");
    ASSERT_NE(none, nullptr);
    EXPECT_GT(none->keypointsPerFrame, 50);
    EXPECT_LE(none->keypointsPerFrame, 1000);
    EXPECT_DOUBLE_EQ(none->repeatability, 1.0);
    EXPECT_DOUBLE_EQ(none->matchingScore, 1.0);
    EXPECT_GT(none->msPerFrame, 0);
    // A brightness offset barely changes anything; rotation costs something.
    EXPECT_GT(res.find(ex, "brightness")->repeatability, 0.8);
    EXPECT_GT(res.find(ex, "rot30")->repeatability, 0.3);
    EXPECT_LT(res.find(ex, "rot30")->repeatability, 1.0);
    EXPECT_GT(res.find(ex, "scale1.5")->repeatability, 0.2);
  }
  // Keypoint noise at the finest scale: none against itself; under a turn
  // a fraction of a pixel, ORB's integer-pixel corners the noisier.
  for (const std::string ex : {"surf", "orb"})
  {
    EXPECT_DOUBLE_EQ(res.find(ex, "none")->localisationSigmaPx, 0.0);
    EXPECT_GT(res.find(ex, "rot30")->localisationMatches, 20u) << ex;
    EXPECT_GT(res.find(ex, "rot30")->localisationSigmaPx, 0.01) << ex;
    EXPECT_LT(res.find(ex, "rot30")->localisationSigmaPx, 1.0) << ex;
  }
  EXPECT_GT(
      res.find("orb", "rot30")->localisationSigmaPx,
      res.find("surf", "rot30")->localisationSigmaPx);
  const auto j = nlohmann::json::parse(CFeatureBench::toJson(res));
  EXPECT_TRUE(j["results"][1].contains("localisation_sigma_px"));
  EXPECT_EQ(j["results"].size(), 8u);
  EXPECT_EQ(j["results"][0]["extractor"], "surf");
  EXPECT_TRUE(j["results"][0].contains("repeatability"));
  const std::string table = CFeatureBench::toTable(res);
  EXPECT_NE(table.find("surf    rot30"), std::string::npos) << table;
  std::filesystem::remove_all(o.input);
}

TEST(CFeatureBench, MissingImageIsReportedByName)
{
  const std::string dir = roislam::testing::makeTempDir("featurebench_missing");
  {
    std::ofstream f(dir + "/rgb.txt");
    f << "1.0 rgb/none.png\n";
  }
  CFeatureBench::TOptions o;
  o.input = dir;
  try
  {
    CFeatureBench(o).run();
    FAIL() << "missing image accepted";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("rgb/none.png"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}
