/* The per-frame ROI landmark pipeline of the dissertation's Test 1:
 * grey -> ROI (CRoiDetector) -> features once on the whole frame
 * (CFeatureExtractor) -> ROI features = subset(roi) -> confirmation: the ROI's
 * features are matched against the previous frame's whole-frame features and
 * the ROI is located there by homography (a ROI seen in two consecutive
 * frames; checking the current ROI against the previous frame rather than the
 * previous ROI against the current frame keeps every record about the current
 * frame's own ROI, with no one-frame lag) -> a confirmed ROI is queried in the
 * CLandmarkDatabase: recall of the best landmark, or a new landmark with its
 * patch, features and 3-D position from depth.
 *
 * Called by CObservationProcessor (and through it by the roi-landmarks app).
 */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <roislam/features/CFeatureExtractor.h>
#include <roislam/io/TRGBDFrame.h>
#include <roislam/landmarks/CLandmarkDatabase.h>
#include <roislam/landmarks/TFrameResult.h>
#include <roislam/landmarks/TPipelineOptions.h>
#include <roislam/landmarks/TRegion.h>
#include <roislam/matching/CFeatureMatcher.h>
#include <roislam/matching/CHomographyLocator.h>
#include <roislam/roi/CRoiDetector.h>

#include <optional>

namespace roislam::landmarks
{
class CRoiLandmarkTracker
{
 public:
  explicit CRoiLandmarkTracker(const TPipelineOptions& options = TPipelineOptions());

  /** Processes the next frame of a sequence. cameraPose: the optical camera's
   *  pose in the world when known (e.g. from SLAM): new landmarks then get a
   *  world position and the database prefilters by position. */
  TFrameResult process(
      const io::TRGBDFrame& frame,
      const std::optional<mrpt::poses::CPose3D>& cameraPose = std::nullopt);

  /** The database step alone: recalls the region as a landmark (a sighting
   *  is added) or stores it as a new one, and fills r's landmark fields
   *  (status Landmark, id, new, box, position, recall figures). No
   *  confirmation against the previous frame. */
  void identify(const TRegion& region, TFrameResult& r);

  /** Forgets the previous frame (the next ROI cannot be confirmed); keeps the
   *  database. */
  void resetSequence();

  const CLandmarkDatabase& database() const { return m_database; }
  CLandmarkDatabase& database() { return m_database; }
  const TPipelineOptions& options() const { return m_options; }

 private:
  TPipelineOptions m_options;
  roi::CRoiDetector m_detector;
  features::CFeatureExtractor m_extractor;
  matching::CFeatureMatcher m_matcher;
  matching::CHomographyLocator m_locator;
  CLandmarkDatabase m_database;

  /** The ROI of a frame with its features, depth and position. */
  TRegion makeRegion(
      const io::TRGBDFrame& frame, const cv::Mat& grey, const cv::Rect& box,
      const features::TFeatureSet& all,
      const std::optional<mrpt::poses::CPose3D>& cameraPose) const;
  /** Re-finds the region in the previous frame (fills matches, false matches). */
  bool confirm(const TRegion& region, TFrameResult& r) const;
  /** Where a recalled landmark's stored point is in the region's frame. */
  std::optional<mrpt::math::TPoint3D> recalledPosition(
      const TRegion& region, const CLandmarkDatabase::TQueryResult& q) const;

  /** Whole-frame features of the previous frame (confirmation target). */
  std::optional<features::TFeatureSet> m_previous;
};
}  // namespace roislam::landmarks
