/* Scores the landmark database against ground truth, replacing the
 * dissertation's counting by eye: each ROI event gets a world position from
 * the ground-truth camera pose of its frame; a recall is a true positive when
 * the recalled landmark (world position at first sight) lies within
 * match_radius of the ROI, else a false positive; a new landmark stored while
 * an earlier landmark lies within match_radius is a false negative
 * (duplicate), else a true negative. precision = TP/(TP+FP),
 * recall = TP/(TP+FN). Used by the roi-landmarks app and its tests.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/io/TumTrajectory.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace roislam::landmarks
{
class CLandmarkScorer
{
 public:
  /** ini section (default "LandmarkScoring"):
   *  - match_radius         metres > 0 (default 0.25)
   *  - max_time_difference  seconds > 0: a frame gets a ground-truth pose only
   *                         when a ground-truth stamp is this close, as the TUM
   *                         tools associate (default 0.02)
   *  - interpolate          bool: interpolate between the two ground-truth
   *                         poses around the frame stamp (default true)
   *  - recall_position      landmark_point | roi_median (default
   *                         landmark_point): where a recall puts the ROI.
   *                         landmark_point: the recalled landmark's stored
   *                         point carried into the frame by the 3-D alignment
   *                         of the recall's matched features, i.e. where the
   *                         match says the landmark is now. roi_median: the
   *                         median 3-D point of all the ROI box's features.
   *                         The box's extent changes from frame to frame, so
   *                         roi_median calls correct recalls false when the
   *                         box gains or loses a background region (e.g.
   *                         fr1/rpy frame 50, ORB: ROI box and located
   *                         landmark box coincide within 2 px, medians 0.28 m
   *                         apart at 3.4 m range). Both are always reported.
   */
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    double match_radius = 0.25;
    double max_time_difference = 0.02;
    bool interpolate = true;
    std::string recall_position = "landmark_point";

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };

  /** One confirmed ROI: recalled as landmarkId, or stored as new landmarkId. */
  struct TEvent
  {
    uint64_t frame = 0;
    double timestamp = 0;
    int32_t landmarkId = -1;
    bool isNew = false;
    /** ROI position in the optical camera frame, if depth allowed it. */
    std::optional<mrpt::math::TPoint3D> roiPosition;
  };

  enum class EOutcome
  {
    TruePositive,
    FalsePositive,
    FalseNegative,
    TrueNegative,
    /** No ground-truth pose, no depth, or the recalled landmark is unscored. */
    Unscored
  };

  struct TScore
  {
    int truePositives = 0;
    int falsePositives = 0;
    int falseNegatives = 0;
    int trueNegatives = 0;
    int unscored = 0;
    /** nullopt when the denominator is 0. */
    std::optional<double> precision;
    std::optional<double> recall;
    /** One per input event, in order. */
    std::vector<EOutcome> outcomes;
  };

  /** groundTruth: camera (optical centre) poses in the world, TUM convention. */
  CLandmarkScorer(const TOptions& options, io::TTrajectory groundTruth);

  /** Ground-truth camera pose at time t, or nullopt when no ground-truth stamp
   *  lies within max_time_difference. */
  std::optional<mrpt::poses::CPose3D> poseAt(double t) const;

  /** Scores events in the order given (the order they happened). */
  TScore score(const std::vector<TEvent>& events) const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
  io::TTrajectory m_gt;
};

const char* toString(CLandmarkScorer::EOutcome outcome);
}  // namespace roislam::landmarks
