#include "roislam/roi/CRoiDetector.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>
#include <roislam/common/IniRead.h>
#include <roislam/roi/LargestComponent.h>

#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace roislam::roi
{
void CRoiDetector::TOptions::setPreset(const std::string& name)
{
  if (name == "small")
  {
    erosions = 6;
    dilations = 7;
  }
  else if (name == "big")
  {
    erosions = 6;
    dilations = 2;
  }
  else if (name != "custom")
    throw std::invalid_argument(
        "unknown ROI preset '" + name + "' (expected small, big or custom)");
  preset = name;
}

void CRoiDetector::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  const std::string p = c.read_string(s, "preset", preset);
  try
  {
    setPreset(p);
  }
  catch (const std::invalid_argument& e)
  {
    common::throwBadIniKey(s, "preset", e.what());
  }
  if (preset == "custom")
  {
    erosions = common::readInt(c, s, "erosions", erosions);
    dilations = common::readInt(c, s, "dilations", dilations);
  }
  else if (c.keyExists(s, "erosions") || c.keyExists(s, "dilations"))
    common::throwBadIniKey(s, "erosions/dilations", "only allowed with preset = custom");
  canny_low = common::readDouble(c, s, "canny_low", canny_low);
  canny_high = common::readDouble(c, s, "canny_high", canny_high);
  min_area_fraction = common::readDouble(c, s, "min_area_fraction", min_area_fraction);
  verify_hue = common::readBool(c, s, "verify_hue", verify_hue);
  hue_canny_low_deg = common::readDouble(c, s, "hue_canny_low_deg", hue_canny_low_deg);
  hue_canny_high_deg = common::readDouble(c, s, "hue_canny_high_deg", hue_canny_high_deg);
  hue_min_saturation = common::readDouble(c, s, "hue_min_saturation", hue_min_saturation);
  hue_min_value = common::readDouble(c, s, "hue_min_value", hue_min_value);
  hue_min_iou = common::readDouble(c, s, "hue_min_iou", hue_min_iou);
  if (erosions < 0)
    common::throwBadIniKey(s, "erosions", "must be >= 0");
  if (dilations < 0)
    common::throwBadIniKey(s, "dilations", "must be >= 0");
  if (!(canny_low >= 0))
    common::throwBadIniKey(s, "canny_low", "must be >= 0");
  if (!(canny_high >= canny_low))
    common::throwBadIniKey(s, "canny_high", "must be >= canny_low");
  if (!(min_area_fraction >= 0 && min_area_fraction < 1))
    common::throwBadIniKey(s, "min_area_fraction", "must be in [0, 1)");
  common::require(
      hue_canny_low_deg > 0 && hue_canny_low_deg <= 180, s, "hue_canny_low_deg", hue_canny_low_deg,
      "in (0, 180]");
  common::require(
      hue_canny_high_deg >= hue_canny_low_deg && hue_canny_high_deg <= 180, s, "hue_canny_high_deg",
      hue_canny_high_deg, "in [hue_canny_low_deg, 180]");
  common::require(
      hue_min_saturation >= 0 && hue_min_saturation <= 1, s, "hue_min_saturation",
      hue_min_saturation, "in [0, 1]");
  common::require(
      hue_min_value >= 0 && hue_min_value <= 1, s, "hue_min_value", hue_min_value, "in [0, 1]");
  common::require(hue_min_iou > 0 && hue_min_iou <= 1, s, "hue_min_iou", hue_min_iou, "in (0, 1]");
}

THueEdgeParams CRoiDetector::TOptions::hueParams() const
{
  THueEdgeParams p;
  p.lowDeg = hue_canny_low_deg;
  p.highDeg = hue_canny_high_deg;
  p.minSaturation = hue_min_saturation;
  p.minValue = hue_min_value;
  return p;
}

void CRoiDetector::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "preset", preset);
  if (preset == "custom")
  {
    c.write(s, "erosions", erosions);
    c.write(s, "dilations", dilations);
  }
  c.write(s, "canny_low", canny_low);
  c.write(s, "canny_high", canny_high);
  c.write(s, "min_area_fraction", min_area_fraction);
  c.write(s, "verify_hue", verify_hue);
  c.write(s, "hue_canny_low_deg", hue_canny_low_deg);
  c.write(s, "hue_canny_high_deg", hue_canny_high_deg);
  c.write(s, "hue_min_saturation", hue_min_saturation);
  c.write(s, "hue_min_value", hue_min_value);
  c.write(s, "hue_min_iou", hue_min_iou);
}

CRoiDetector::CRoiDetector() : CRoiDetector(TOptions()) {}

CRoiDetector::CRoiDetector(const TOptions& options) : m_options(options)
{
  if (m_options.erosions < 0 || m_options.dilations < 0)
    throw std::invalid_argument("CRoiDetector: erosions and dilations must be >= 0");
}

void CRoiDetector::morphology(cv::Mat& edges) const
{
  // See the TOptions comment: the dissertation's erosion grows the (black)
  // edges, i.e. cv::dilate on our white-edge mask, and vice versa.
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  if (m_options.erosions > 0)
    cv::dilate(edges, edges, kernel, cv::Point(-1, -1), m_options.erosions);
  if (m_options.dilations > 0)
    cv::erode(edges, edges, kernel, cv::Point(-1, -1), m_options.dilations);
}

cv::Mat CRoiDetector::foregroundMask(const cv::Mat& image) const
{
  cv::Mat grey = image;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  if (grey.type() != CV_8UC1)
    throw std::invalid_argument("CRoiDetector: expected an 8-bit grey or BGR image");
  cv::Mat edges;
  cv::Canny(grey, edges, m_options.canny_low, m_options.canny_high, 3);
  morphology(edges);
  return edges;
}

cv::Mat CRoiDetector::hueForegroundMask(const cv::Mat& bgr) const
{
  cv::Mat edges = hueEdges(bgr, m_options.hueParams());
  morphology(edges);
  return edges;
}

std::optional<TRoi> CRoiDetector::largestRoi(const cv::Mat& mask) const
{
  // Only the largest component is needed: run-length labelling finds it in a
  // fraction of connectedComponentsWithStats' time (LargestComponent.h).
  const auto best = largestComponent(mask);
  if (!best || best->area < m_options.min_area_fraction * static_cast<double>(mask.total()))
    return std::nullopt;
  TRoi roi;
  roi.box = best->box;
  roi.componentArea = best->area;
  return roi;
}

std::optional<TRoi> CRoiDetector::detect(const cv::Mat& image) const
{
  if (image.channels() == 3)
  {
    cv::Mat grey;
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
    return detect(grey, image);
  }
  return detect(image, cv::Mat());
}

std::optional<TRoi> CRoiDetector::detect(const cv::Mat& grey, const cv::Mat& bgr) const
{
  return detectDetailed(grey, bgr).roi;
}

TRoiDetection CRoiDetector::detectDetailed(const cv::Mat& grey, const cv::Mat& bgr) const
{
  TRoiDetection d;
  d.grey = largestRoi(foregroundMask(grey));
  if (!m_options.verify_hue)
  {
    d.roi = d.grey;
    return d;
  }
  if (bgr.type() != CV_8UC3)
    throw std::invalid_argument("[RoiDetector] verify_hue needs the colour image (8-bit BGR)");
  if (!d.grey)
    return d;
  d.hue = largestRoi(hueForegroundMask(bgr));
  if (d.hue)
  {
    const cv::Rect &a = d.grey->box, &b = d.hue->box;
    d.iou = static_cast<double>((a & b).area()) / static_cast<double>((a | b).area());
  }
  if (d.iou >= m_options.hue_min_iou)
    d.roi = d.grey;
  return d;
}
}  // namespace roislam::roi
