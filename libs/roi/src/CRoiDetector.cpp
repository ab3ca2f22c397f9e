#include "roislam/roi/CRoiDetector.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>
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
    erosions = c.read_int(s, "erosions", erosions);
    dilations = c.read_int(s, "dilations", dilations);
  }
  else if (c.keyExists(s, "erosions") || c.keyExists(s, "dilations"))
    common::throwBadIniKey(s, "erosions/dilations", "only allowed with preset = custom");
  canny_low = c.read_double(s, "canny_low", canny_low);
  canny_high = c.read_double(s, "canny_high", canny_high);
  min_area_fraction = c.read_double(s, "min_area_fraction", min_area_fraction);
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
}

CRoiDetector::CRoiDetector() : CRoiDetector(TOptions()) {}

CRoiDetector::CRoiDetector(const TOptions& options) : m_options(options)
{
  if (m_options.erosions < 0 || m_options.dilations < 0)
    throw std::invalid_argument("CRoiDetector: erosions and dilations must be >= 0");
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
  // See the TOptions comment: the dissertation's erosion grows the (black)
  // edges, i.e. cv::dilate on our white-edge mask, and vice versa.
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  if (m_options.erosions > 0)
    cv::dilate(edges, edges, kernel, cv::Point(-1, -1), m_options.erosions);
  if (m_options.dilations > 0)
    cv::erode(edges, edges, kernel, cv::Point(-1, -1), m_options.dilations);
  return edges;
}

std::optional<TRoi> CRoiDetector::detect(const cv::Mat& image) const
{
  const cv::Mat mask = foregroundMask(image);
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
}  // namespace roislam::roi
