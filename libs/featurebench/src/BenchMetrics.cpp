/* Repeatability and matching score (see BenchMetrics.h). */
#include <roislam/common/Median.h>
#include <roislam/featurebench/BenchMetrics.h>

#include <algorithm>
#include <cmath>
#include <opencv2/features2d.hpp>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace roislam::featurebench
{
namespace
{
cv::Point2d apply(const cv::Matx33d& H, cv::Point2d p)
{
  const cv::Vec3d q = H * cv::Vec3d(p.x, p.y, 1.0);
  return {q[0] / q[2], q[1] / q[2]};
}

bool inside(cv::Point2d p, const cv::Size& s, double margin)
{
  return p.x >= margin && p.y >= margin && p.x <= s.width - 1 - margin &&
         p.y <= s.height - 1 - margin;
}

/** Local linear scale of H at p: sqrt of the Jacobian determinant. */
double localScale(const cv::Matx33d& H, cv::Point2d p)
{
  const cv::Point2d o = apply(H, p), ex = apply(H, p + cv::Point2d(1, 0)),
                    ey = apply(H, p + cv::Point2d(0, 1));
  const cv::Point2d a = ex - o, b = ey - o;
  return std::sqrt(std::abs(a.x * b.y - a.y * b.x));
}
/** The keypoints both images show (inside the border margin in their own
 *  image and, mapped through H, in the other), as indices into kpsA / kpsB,
 *  with the A points' mapped positions and local scales. */
struct TCommonKeypoints
{
  std::vector<int> inA, inB;
  std::vector<cv::Point2d> mappedA;
  std::vector<double> scaleA;
};

TCommonKeypoints commonKeypoints(
    const std::vector<cv::KeyPoint>& kpsA, const std::vector<cv::KeyPoint>& kpsB,
    const cv::Matx33d& H, const cv::Size& sizeA, const cv::Size& sizeB, double margin)
{
  const cv::Matx33d Hinv = H.inv();
  TCommonKeypoints common;
  for (size_t i = 0; i < kpsA.size(); ++i)
  {
    const cv::Point2d p(kpsA[i].pt);
    const cv::Point2d q = apply(H, p);
    if (!inside(p, sizeA, margin) || !inside(q, sizeB, margin))
      continue;
    common.inA.push_back(static_cast<int>(i));
    common.mappedA.push_back(q);
    common.scaleA.push_back(localScale(H, p));
  }
  for (size_t j = 0; j < kpsB.size(); ++j)
  {
    const cv::Point2d p(kpsB[j].pt);
    if (inside(p, sizeB, margin) && inside(apply(Hinv, p), sizeA, margin))
      common.inB.push_back(static_cast<int>(j));
  }
  return common;
}

/** Whether a common keypoint of A (index into TCommonKeypoints::inA) and a
 *  keypoint of B correspond under the criterion. */
class CCorrespondenceTest
{
 public:
  /** Throws std::invalid_argument on bad overlap parameters. */
  CCorrespondenceTest(
      const std::vector<cv::KeyPoint>& kpsA, const std::vector<cv::KeyPoint>& kpsB,
      const TCommonKeypoints& common, const TCorrespondenceCriterion& crit)
      : m_kpsA(kpsA),
        m_kpsB(kpsB),
        m_common(common),
        m_crit(crit),
        m_tol2(crit.pixelTolerance * crit.pixelTolerance),
        m_logR(std::log(crit.maxScaleRatio)),
        m_overlap(crit.mode == TCorrespondenceCriterion::EMode::Overlap)
  {
    if (m_overlap && !(crit.regionRadiusPerSize > 0 && crit.normalisedRadius > 0 &&
                       crit.maxOverlapError > 0 && crit.maxOverlapError <= 1))
      throw std::invalid_argument("evaluatePair: invalid overlap criterion parameters");
  }

  // The score sorts candidate pairs (closest first): squared distance in
  // pixel mode, overlap error in overlap mode.
  bool operator()(size_t ia, int j, double& score) const
  {
    const cv::Point2d d = m_common.mappedA[ia] - cv::Point2d(m_kpsB[j].pt);
    const double d2 = d.dot(d);
    const double sa = m_kpsA[m_common.inA[ia]].size * m_common.scaleA[ia], sb = m_kpsB[j].size;
    if (m_overlap)
    {
      if (!(sa > 0) || !(sb > 0))
        return false;  // no region
      // Mapped reference region normalised to normalisedRadius, the same
      // factor applied to the other region and to the centre distance.
      const double ra = m_crit.regionRadiusPerSize * sa, rb = m_crit.regionRadiusPerSize * sb;
      const double f = m_crit.normalisedRadius / ra;
      score = circleOverlapError(ra * f, rb * f, std::sqrt(d2) * f);
      return score < m_crit.maxOverlapError;
    }
    score = d2;
    if (d2 > m_tol2)
      return false;
    if (!(sa > 0) || !(sb > 0))
      return true;  // no scale information: position only
    return std::abs(std::log(sb / sa)) <= m_logR;
  }

 private:
  const std::vector<cv::KeyPoint>& m_kpsA;
  const std::vector<cv::KeyPoint>& m_kpsB;
  const TCommonKeypoints& m_common;
  const TCorrespondenceCriterion& m_crit;
  const double m_tol2, m_logR;
  const bool m_overlap;
};

// Geometric correspondences, one-to-one, closest pairs first.
std::size_t countCorrespondences(
    const TCommonKeypoints& common, const CCorrespondenceTest& consistent)
{
  const auto& inA = common.inA;
  const auto& inB = common.inB;
  std::vector<std::tuple<double, int, int>> cand;
  for (size_t ia = 0; ia < inA.size(); ++ia)
    for (size_t ib = 0; ib < inB.size(); ++ib)
    {
      double d2;
      if (consistent(ia, inB[ib], d2))
        cand.emplace_back(d2, static_cast<int>(ia), static_cast<int>(ib));
    }
  std::sort(cand.begin(), cand.end());
  std::vector<char> usedA(inA.size(), 0), usedB(inB.size(), 0);
  std::size_t correspondences = 0;
  for (const auto& [d2, ia, ib] : cand)
  {
    if (usedA[ia] || usedB[ib])
      continue;
    usedA[ia] = usedB[ib] = 1;
    ++correspondences;
  }
  return correspondences;
}

/** The smallest positive keypoint.size, or 0 when none has one. */
double finestSize(const std::vector<cv::KeyPoint>& kps)
{
  double s0 = 0;
  for (const auto& k : kps)
    if (k.size > 0 && (s0 == 0 || k.size < s0))
      s0 = k.size;
  return s0;
}

/** Whether a keypoint was detected at its image's finest scale s0. */
bool atFinestScale(const cv::KeyPoint& k, double s0)
{
  return !(k.size > 0) || !(s0 > 0) || k.size <= kFinestScaleRatio * s0;
}

/** Common keypoints of A whose descriptor nearest neighbour among B's common
 *  keypoints is a geometric correspondence; the finest-scale ones' errors
 *  against H go to *finestErrors. */
std::size_t countCorrectMatches(
    const cv::Mat& descA, const cv::Mat& descB, int normType, const TCommonKeypoints& common,
    const CCorrespondenceTest& consistent, const std::vector<cv::KeyPoint>& kpsA,
    const std::vector<cv::KeyPoint>& kpsB, const cv::Matx33d& H, std::vector<double>* finestErrors)
{
  const double s0a = finestSize(kpsA), s0b = finestSize(kpsB);
  const auto& inA = common.inA;
  const auto& inB = common.inB;
  cv::Mat qa(static_cast<int>(inA.size()), descA.cols, descA.type());
  cv::Mat tb(static_cast<int>(inB.size()), descB.cols, descB.type());
  for (size_t k = 0; k < inA.size(); ++k)
    descA.row(inA[k]).copyTo(qa.row(static_cast<int>(k)));
  for (size_t k = 0; k < inB.size(); ++k)
    descB.row(inB[k]).copyTo(tb.row(static_cast<int>(k)));
  std::vector<cv::DMatch> matches;
  cv::BFMatcher(normType).match(qa, tb, matches);
  std::size_t correct = 0;
  for (const auto& mt : matches)
  {
    double d2;
    if (!consistent(static_cast<size_t>(mt.queryIdx), inB[mt.trainIdx], d2))
      continue;
    ++correct;
    const cv::KeyPoint& a = kpsA[static_cast<std::size_t>(inA[mt.queryIdx])];
    const cv::KeyPoint& b = kpsB[static_cast<std::size_t>(inB[mt.trainIdx])];
    if (finestErrors && atFinestScale(a, s0a) && atFinestScale(b, s0b))
    {
      const cv::Vec3d p = H * cv::Vec3d(a.pt.x, a.pt.y, 1.0);
      finestErrors->push_back(b.pt.x - p[0] / p[2]);
      finestErrors->push_back(b.pt.y - p[1] / p[2]);
    }
  }
  return correct;
}
}  // namespace

double circleOverlapError(double r1, double r2, double d)
{
  if (!(r1 > 0) || !(r2 > 0))
    return 1.0;
  d = std::abs(d);
  const double a1 = CV_PI * r1 * r1, a2 = CV_PI * r2 * r2;
  double inter;
  if (d >= r1 + r2)
    inter = 0;
  else if (d <= std::abs(r1 - r2))
    inter = std::min(a1, a2);
  else
  {
    // Two circular segments (lens area).
    const double c1 = std::clamp((d * d + r1 * r1 - r2 * r2) / (2 * d * r1), -1.0, 1.0);
    const double c2 = std::clamp((d * d + r2 * r2 - r1 * r1) / (2 * d * r2), -1.0, 1.0);
    const double k = (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2);
    inter = r1 * r1 * std::acos(c1) + r2 * r2 * std::acos(c2) - 0.5 * std::sqrt(std::max(0.0, k));
  }
  return 1.0 - inter / (a1 + a2 - inter);
}

double localisationSigma(std::vector<double> errors)
{
  if (errors.empty())
    return 0;
  for (double& e : errors)
    e = std::abs(e);
  return 1.482602218505602 * common::upperMedian(std::move(errors)) / std::sqrt(2.0);
}

TPairMetrics evaluatePair(
    const std::vector<cv::KeyPoint>& kpsA, const cv::Mat& descA,
    const std::vector<cv::KeyPoint>& kpsB, const cv::Mat& descB, const cv::Matx33d& H,
    const cv::Size& sizeA, const cv::Size& sizeB, int normType,
    const TCorrespondenceCriterion& crit, bool finestScaleErrors)
{
  const bool withDesc = !descA.empty() && !descB.empty();
  if (withDesc &&
      (descA.rows != static_cast<int>(kpsA.size()) || descB.rows != static_cast<int>(kpsB.size()) ||
       descA.cols != descB.cols || descA.type() != descB.type()))
    throw std::invalid_argument("evaluatePair: descriptors do not match the keypoints");
  const TCommonKeypoints common = commonKeypoints(kpsA, kpsB, H, sizeA, sizeB, crit.borderMargin);

  TPairMetrics m;
  m.commonA = common.inA.size();
  m.commonB = common.inB.size();
  const std::size_t denom = std::min(m.commonA, m.commonB);
  if (denom == 0)
    return m;

  const CCorrespondenceTest consistent(kpsA, kpsB, common, crit);
  m.correspondences = countCorrespondences(common, consistent);
  m.repeatability = static_cast<double>(m.correspondences) / static_cast<double>(denom);
  if (withDesc)
  {
    m.correctMatches = countCorrectMatches(
        descA, descB, normType, common, consistent, kpsA, kpsB, H,
        finestScaleErrors ? &m.finestScaleErrors : nullptr);
    m.matchingScore = static_cast<double>(m.correctMatches) / static_cast<double>(denom);
  }
  return m;
}
}  // namespace roislam::featurebench
