#include "roislam/matching/CHomographyLocator.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace roislam::matching
{
namespace
{
void validate(const CHomographyLocator::TOptions& o, const std::string& s)
{
  if (!(o.ransac_reproj_threshold > 0))
    common::throwBadIniKey(s, "ransac_reproj_threshold", "must be > 0");
  if (o.ransac_max_iters <= 0)
    common::throwBadIniKey(s, "ransac_max_iters", "must be > 0");
  if (!(o.ransac_confidence > 0 && o.ransac_confidence < 1))
    common::throwBadIniKey(s, "ransac_confidence", "must be in (0, 1)");
  if (o.min_inliers < 4)
    common::throwBadIniKey(s, "min_inliers", "must be >= 4");
  if (!(o.min_inlier_ratio >= 0 && o.min_inlier_ratio <= 1))
    common::throwBadIniKey(s, "min_inlier_ratio", "must be in [0, 1]");
  if (!(o.max_scale_change > 1))
    common::throwBadIniKey(s, "max_scale_change", "must be > 1");
}
}  // namespace

void CHomographyLocator::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  ransac_reproj_threshold = c.read_double(s, "ransac_reproj_threshold", ransac_reproj_threshold);
  ransac_max_iters = c.read_int(s, "ransac_max_iters", ransac_max_iters);
  ransac_confidence = c.read_double(s, "ransac_confidence", ransac_confidence);
  min_inliers = c.read_int(s, "min_inliers", min_inliers);
  min_inlier_ratio = c.read_double(s, "min_inlier_ratio", min_inlier_ratio);
  max_scale_change = c.read_double(s, "max_scale_change", max_scale_change);
  validate(*this, s);
}

void CHomographyLocator::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "ransac_reproj_threshold", ransac_reproj_threshold);
  c.write(s, "ransac_max_iters", ransac_max_iters);
  c.write(s, "ransac_confidence", ransac_confidence);
  c.write(s, "min_inliers", min_inliers);
  c.write(s, "min_inlier_ratio", min_inlier_ratio);
  c.write(s, "max_scale_change", max_scale_change);
}

CHomographyLocator::CHomographyLocator() : CHomographyLocator(TOptions()) {}

CHomographyLocator::CHomographyLocator(const TOptions& options) : m_options(options)
{
  validate(m_options, "HomographyLocator");
}

std::optional<THomographyResult> CHomographyLocator::locate(
    const features::TFeatureSet& reference, const cv::Rect& refRoi,
    const features::TFeatureSet& other, const cv::Size& otherSize,
    const std::vector<cv::DMatch>& matches) const
{
  const int n = static_cast<int>(matches.size());
  if (n < std::max(4, m_options.min_inliers))
    return std::nullopt;

  std::vector<cv::Point2f> src, dst;
  src.reserve(matches.size());
  dst.reserve(matches.size());
  for (const auto& m : matches)
  {
    src.push_back(reference.keypoints.at(static_cast<std::size_t>(m.queryIdx)).pt);
    dst.push_back(other.keypoints.at(static_cast<std::size_t>(m.trainIdx)).pt);
  }
  cv::Mat inlierMask;
  cv::Mat H = cv::findHomography(
      src, dst, cv::RANSAC, m_options.ransac_reproj_threshold, inlierMask,
      m_options.ransac_max_iters, m_options.ransac_confidence);
  if (H.empty())
    return std::nullopt;

  THomographyResult r;
  r.numMatches = n;
  for (int i = 0; i < n; ++i)
    if (inlierMask.at<uchar>(i))
      r.inliers.push_back(matches[static_cast<std::size_t>(i)]);
  const int nIn = static_cast<int>(r.inliers.size());
  if (nIn < m_options.min_inliers || nIn < m_options.min_inlier_ratio * n)
    return std::nullopt;

  const std::vector<cv::Point2f> refCorners = {
      cv::Point2f(refRoi.x, refRoi.y), cv::Point2f(refRoi.x + refRoi.width, refRoi.y),
      cv::Point2f(refRoi.x + refRoi.width, refRoi.y + refRoi.height),
      cv::Point2f(refRoi.x, refRoi.y + refRoi.height)};
  cv::perspectiveTransform(refCorners, r.corners, H);

  // Reject physically implausible homographies: a rigid planar-ish patch seen
  // from a moving camera maps to a convex quadrilateral of similar area.
  if (!cv::isContourConvex(r.corners))
    return std::nullopt;
  const double area = std::abs(cv::contourArea(r.corners));
  const double refArea = static_cast<double>(refRoi.area());
  if (refArea <= 0 || !(area > refArea / m_options.max_scale_change) ||
      !(area < refArea * m_options.max_scale_change))
    return std::nullopt;

  const cv::Rect bounds = cv::boundingRect(r.corners);
  r.box = bounds & cv::Rect(0, 0, otherSize.width, otherSize.height);
  if (r.box.area() <= 0)
    return std::nullopt;

  // The dissertation's false match: a matched feature landing outside the ROI
  // as located in the other image.
  for (const auto& p : dst)
    if (cv::pointPolygonTest(r.corners, p, false) < 0)
      ++r.falseMatches;
  r.H = H;
  return r;
}
}  // namespace roislam::matching
