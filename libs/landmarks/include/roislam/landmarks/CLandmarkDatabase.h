/* The landmark database of the dissertation's Test 1: starts empty; a
 * confirmed ROI is matched against the stored landmarks (descriptor matching
 * + RANSAC homography verification, then, where the features have depth, a
 * RANSAC rigid 3-D alignment of the homography inliers: a recall must be the
 * same physical surface, not just a similar-looking one); the landmark with
 * the most inliers is recalled, otherwise the ROI becomes a new landmark.
 *
 * To keep a query cheap as the database grows, at most max_candidates
 * landmarks are verified: when there are more, every ROI feature votes for the
 * landmark that owns its nearest descriptor among all stored descriptors (one
 * FLANN call, whatever the configured matcher) and the most voted landmarks
 * are verified. When world
 * positions are known (a pose was given), only landmarks within
 * prefilter_radius of the query are considered at all.
 *
 * Used by CRoiLandmarkTracker; saved/loaded by the roi-landmarks app.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/serialization/CSerializable.h>
#include <roislam/landmarks/CLandmark.h>
#include <roislam/landmarks/FeatureGeometry.h>
#include <roislam/matching/CFeatureIndex.h>
#include <roislam/matching/CFeatureMatcher.h>
#include <roislam/matching/CHomographyLocator.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace roislam::landmarks
{
class CLandmarkDatabase : public mrpt::serialization::CSerializable
{
  DEFINE_SERIALIZABLE(CLandmarkDatabase, roislam::landmarks)

 public:
  /** ini section (default "LandmarkDatabase"):
   *  - max_candidates    int >= 0: landmarks verified per query by homography;
   *                      0 = all (default 8)
   *  - prefilter_radius  metres >= 0: when both the query and a landmark have
   *                      world positions, landmarks farther than this are not
   *                      candidates; 0 = off (default 1.5)
   *  - min_votes         int >= 0: a voted candidate needs at least this many
   *                      votes (default 4)
   *  - min_overlap       [0,1]: a recall needs the landmark, located in the
   *                      query frame by the homography, to overlap the ROI
   *                      with at least this intersection-over-union; 0 = off
   *                      (default 0: the ROI detector's box varies a lot
   *                      between frames for the same surface)
   *  - rigid_threshold   metres > 0: inlier distance of the 3-D alignment
   *                      (default 0.05: 3 sigma of Kinect depth noise at about
   *                      3 m, Khoshelham & Elberink 2012)
   *  - min_rigid_inliers int >= 3: homography inliers with depth needed to
   *                      run the 3-D check; with fewer the homography alone
   *                      decides (default 6)
   *  - min_rigid_fraction [0,1]: share of those pairs the alignment must
   *                      explain for the recall to stand (default 0.5: a
   *                      majority)
   */
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    int max_candidates = 8;
    double prefilter_radius = 1.5;
    int min_votes = 4;
    double min_overlap = 0;
    double rigid_threshold = 0.05;
    int min_rigid_inliers = 6;
    double min_rigid_fraction = 0.5;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };

  /** Outcome of a query. */
  struct TQueryResult
  {
    /** The recalled landmark, or nullopt: the ROI is new. */
    std::optional<int32_t> landmarkId;
    /** Homography verification of the recalled landmark. */
    int inliers = 0;
    int matches = 0;
    int falseMatches = 0;
    /** The recalled landmark's ROI located in the query frame, and its
     *  intersection-over-union with the query ROI. */
    cv::Rect locatedBox;
    double overlap = 0;
    /** Homography inliers of the recall: queryIdx indexes the landmark's
     *  features, trainIdx the query ROI's. */
    std::vector<cv::DMatch> inlierMatches;
    /** The 3-D check of the recall, when enough inliers had depth: pose
     *  maps the landmark's first-sight camera frame into the query frame. */
    std::optional<TRigidFit> rigid;
    /** Landmarks verified by homography for this query. */
    int candidates = 0;
  };

  CLandmarkDatabase();
  CLandmarkDatabase(
      const TOptions& options, const matching::CFeatureMatcher::TOptions& matcherOptions,
      const matching::CHomographyLocator::TOptions& locatorOptions);

  /** Matches a ROI's features (keypoints in its frame's pixels) against the
   *  database; roiBox is the ROI in that frame (for the overlap test).
   *  roiPoints: optical-frame 3-D points of the ROI features (parallel to
   *  roiFeatures, NaN = no depth; empty = no 3-D check). worldPosition
   *  enables the position prefilter. */
  TQueryResult query(
      const features::TFeatureSet& roiFeatures, const cv::Rect& roiBox, const cv::Size& imageSize,
      const std::vector<mrpt::math::TPoint3D>& roiPoints = {},
      const std::optional<mrpt::math::TPoint3D>& worldPosition = std::nullopt) const;

  /** Stores a new landmark; assigns and returns its id (its index). */
  int32_t add(CLandmark landmark);
  /** Appends a sighting to landmark id; throws std::out_of_range on a bad id. */
  void addSighting(int32_t id, const TLandmarkSighting& sighting);

  const std::vector<CLandmark>& landmarks() const { return m_landmarks; }
  const CLandmark& landmark(int32_t id) const;
  std::size_t size() const { return m_landmarks.size(); }
  bool empty() const { return m_landmarks.empty(); }
  void clear();

  /** Writes the database (gzip-compressed MRPT archive) through a temporary
   *  file renamed on success; throws std::runtime_error naming the file. */
  void save(const std::string& file) const;
  /** Replaces the landmarks with those of a file written by save() (gzip or
   *  plain); keeps this object's options. Throws naming the file. */
  void load(const std::string& file);

  const TOptions& options() const { return m_options; }

 private:
  std::vector<int32_t> candidates(
      const features::TFeatureSet& roiFeatures,
      const std::optional<mrpt::math::TPoint3D>& worldPosition) const;

  TOptions m_options;
  matching::CFeatureMatcher m_matcher;
  /** Nearest-neighbour matcher (no ratio test) for the candidate vote. */
  matching::CFeatureMatcher m_voteMatcher;
  matching::CHomographyLocator m_locator;
  std::vector<CLandmark> m_landmarks;

  /** Search structure over all landmark descriptors stacked, and the
   *  landmark owning each row. Immutable once built, so const queries from
   *  several threads share it. */
  struct TVoteIndex
  {
    std::vector<int32_t> owner;
    std::shared_ptr<const matching::CFeatureIndex> index;
  };
  /** The vote index, built on the first query after add()/clear()/load
   *  (under m_voteMutex, so concurrent const queries are safe). */
  std::shared_ptr<const TVoteIndex> voteIndex() const;

  mutable std::shared_ptr<const TVoteIndex> m_vote;
  /** Shared by copies (serialization clones the database): it only guards
   *  the lazy build. */
  std::shared_ptr<std::mutex> m_voteMutex = std::make_shared<std::mutex>();
};
}  // namespace roislam::landmarks
