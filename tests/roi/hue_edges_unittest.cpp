/* The hue detector of [RoiDetector] verify_hue: hue edges are circular (a
 * step across 179/0 is as small as it is), grey and dark pixels make none,
 * and the verification accepts a ROI the colour agrees with and rejects one
 * it does not; bad option values name their key. */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/roi/CRoiDetector.h>
#include <roislam/roi/HueEdges.h>

#include <opencv2/imgproc.hpp>
#include <random>

using namespace roislam::roi;

namespace
{
/** A 640x480 image of two vertical halves with OpenCV hues h1 | h2 (0..179). */
cv::Mat halves(int h1, int h2, int s = 200, int v = 200)
{
  cv::Mat hsv(480, 640, CV_8UC3, cv::Scalar(h1, s, v));
  hsv(cv::Rect(320, 0, 320, 480)).setTo(cv::Scalar(h2, s, v));
  cv::Mat bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  return bgr;
}

int edgePixels(const cv::Mat& bgr)
{
  return cv::countNonZero(hueEdges(bgr, THueEdgeParams()));
}

/** Mid-grey image with a patch of small squares: grey-textured or, with
 *  colourful, of random saturated hues at the same brightness pattern. */
cv::Mat patchImage(const cv::Rect& patch, bool colourful, unsigned seed = 1)
{
  cv::Mat hsv(480, 640, CV_8UC3, cv::Scalar(0, 0, 128));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> hue(0, 179), level(0, 1);
  for (int y = patch.y; y + 10 <= patch.y + patch.height; y += 10)
    for (int x = patch.x; x + 10 <= patch.x + patch.width; x += 10)
    {
      const int v = level(rng) ? 250 : 40;
      hsv(cv::Rect(x, y, 10, 10))
          .setTo(colourful ? cv::Scalar(hue(rng), 230, std::max(v, 160)) : cv::Scalar(0, 0, v));
    }
  cv::Mat bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  return bgr;
}

double iou(const cv::Rect& a, const cv::Rect& b)
{
  return static_cast<double>((a & b).area()) / static_cast<double>((a | b).area());
}

CRoiDetector hueVerifying()
{
  CRoiDetector::TOptions o;
  o.verify_hue = true;
  return CRoiDetector(o);
}
}  // namespace

TEST(HueEdges, StepsAcrossTheWrapAreAsSmallAsTheyAre)
{
  // 178 | 1 is 3 units = 6 degrees: no edge, although raw hue jumps by 177.
  EXPECT_EQ(edgePixels(halves(178, 1)), 0);
  cv::Mat hueChannel, rawEdges;
  cv::Mat hsv;
  cv::cvtColor(halves(178, 1), hsv, cv::COLOR_BGR2HSV);
  cv::extractChannel(hsv, hueChannel, 0);
  cv::Canny(hueChannel, rawEdges, 20, 40);
  EXPECT_GT(cv::countNonZero(rawEdges), 400);  // what a non-circular hue would do
  // 50 degrees are 50 degrees on either side of the wrap (170 | 15 and 80 | 105).
  const int acrossWrap = edgePixels(halves(170, 15));
  const int inside = edgePixels(halves(80, 105));
  EXPECT_GT(inside, 400);
  EXPECT_EQ(acrossWrap, inside);
  // Opposite hues: an edge along the whole border, only there.
  const cv::Mat e = hueEdges(halves(0, 90), THueEdgeParams());
  EXPECT_GT(cv::countNonZero(e(cv::Rect(316, 0, 8, 480))), 470);
  EXPECT_EQ(cv::countNonZero(e(cv::Rect(0, 0, 300, 480))), 0);
}

TEST(HueEdges, GreyAndDarkPixelsHaveNoHue)
{
  // A grey image full of strong grey edges: no hue edge at all.
  const cv::Mat grey = patchImage(cv::Rect(100, 100, 300, 200), false);
  EXPECT_EQ(edgePixels(grey), 0);
  EXPECT_EQ(cv::countNonZero(reliableHueMask(grey, THueEdgeParams())), 0);
  // Opposite hues, but too dark (value 0.1) or too pale (saturation 0.1).
  EXPECT_EQ(edgePixels(halves(0, 90, 200, 25)), 0);
  EXPECT_EQ(edgePixels(halves(0, 90, 25, 200)), 0);
  // A coloured half next to a grey half: the border is the grey detector's
  // business, not a hue edge.
  cv::Mat mixed = halves(0, 90);
  mixed(cv::Rect(320, 0, 320, 480)).setTo(cv::Scalar(120, 120, 120));
  EXPECT_EQ(edgePixels(mixed), 0);
  EXPECT_THROW(hueEdges(cv::Mat(10, 10, CV_8UC1), THueEdgeParams()), std::invalid_argument);
}

TEST(CRoiDetectorHue, AcceptsAColourfulPatchAndRejectsAGreyOne)
{
  const cv::Rect patch(200, 120, 240, 180);
  const auto det = hueVerifying();

  const cv::Mat colourful = patchImage(patch, true);
  cv::Mat grey;
  cv::cvtColor(colourful, grey, cv::COLOR_BGR2GRAY);
  const auto ok = det.detectDetailed(grey, colourful);
  ASSERT_TRUE(ok.grey && ok.hue && ok.roi);
  EXPECT_GE(iou(ok.hue->box, patch), 0.7) << ok.hue->box;
  EXPECT_GE(ok.iou, 0.5);
  EXPECT_EQ(ok.roi->box, ok.grey->box);  // the accepted box is the grey detector's
  EXPECT_FALSE(ok.rejectedByHue());
  ASSERT_TRUE(det.detect(colourful));  // one-image overload

  // The same detail in grey: the grey detector finds it, the hue detector
  // nothing, so the frame has no ROI.
  const cv::Mat plain = patchImage(patch, false);
  cv::cvtColor(plain, grey, cv::COLOR_BGR2GRAY);
  const auto rejected = det.detectDetailed(grey, plain);
  EXPECT_TRUE(rejected.grey);
  EXPECT_FALSE(rejected.hue);
  EXPECT_FALSE(rejected.roi);
  EXPECT_TRUE(rejected.rejectedByHue());
  // Without verification the grey patch is the ROI.
  EXPECT_TRUE(CRoiDetector().detect(plain));

  // Detail in grey, colour somewhere else: the boxes disagree.
  cv::Mat elsewhere = plain.clone();
  patchImage(cv::Rect(20, 330, 120, 120), true, 7)(cv::Rect(20, 330, 120, 120))
      .copyTo(elsewhere(cv::Rect(20, 330, 120, 120)));
  cv::cvtColor(elsewhere, grey, cv::COLOR_BGR2GRAY);
  const auto apart = det.detectDetailed(grey, elsewhere);
  ASSERT_TRUE(apart.grey && apart.hue);
  EXPECT_LT(apart.iou, 0.5);
  EXPECT_FALSE(apart.roi);

  // verify_hue needs the colour image.
  EXPECT_THROW(det.detect(grey), std::invalid_argument);
}

TEST(CRoiDetectorHue, BadValuesNameTheirKey)
{
  const auto errorOf = [](const std::string& key, const std::string& value)
  {
    mrpt::config::CConfigFileMemory cfg;
    cfg.write("RoiDetector", key, value);
    CRoiDetector::TOptions o;
    try
    {
      o.loadFromConfigFile(cfg, "RoiDetector");
    }
    catch (const std::exception& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"verify_hue", "maybe"},
           {"verify_hue", "2"},
           {"hue_canny_low_deg", "0"},
           {"hue_canny_low_deg", "abc"},
           {"hue_canny_high_deg", "10"},  // below the low threshold (20)
           {"hue_canny_high_deg", "190"},
           {"hue_min_saturation", "-0.1"},
           {"hue_min_value", "1.5"},
           {"hue_min_iou", "0"},
           {"hue_min_iou", "1.2"},
           {"canny_low", "x"}})
  {
    const std::string e = errorOf(key, value);
    EXPECT_NE(e.find("[RoiDetector] " + key), std::string::npos)
        << key << "=" << value << ": " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  EXPECT_EQ(errorOf("verify_hue", "true"), "");

  CRoiDetector::TOptions a;
  a.verify_hue = true;
  a.hue_canny_low_deg = 15;
  a.hue_min_iou = 0.3;
  mrpt::config::CConfigFileMemory cfg;
  a.saveToConfigFile(cfg, "RoiDetector");
  CRoiDetector::TOptions b;
  b.loadFromConfigFile(cfg, "RoiDetector");
  EXPECT_TRUE(b.verify_hue);
  EXPECT_DOUBLE_EQ(b.hue_canny_low_deg, 15);
  EXPECT_DOUBLE_EQ(b.hue_min_iou, 0.3);
}
