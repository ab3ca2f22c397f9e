/* Estimates where an unregistered depth camera sits beside the colour camera,
 * and the colour camera's intrinsics, from a sequence's own frames: for a
 * sensor whose calibration is not known (7-Scenes publishes the depth camera
 * alone; TSensorDescription's estimate_registration). Called by
 * CTumFrameSource and COpenNI2FrameSource (recordings) before the first
 * frame; tests call it directly.
 *
 * The measurement: a depth discontinuity (a pixel whose neighbour is much
 * farther, across a band of missing readings if need be) is an object's
 * silhouette, and the colour image has an edge there. Each silhouette point
 * is lifted with the depth camera, moved into the colour camera by
 * depth_pose_in_colour and projected with the colour intrinsics (and
 * distortion); the residual is its distance, across the edge, to the
 * nearest colour (Canny) edge at that edge's sub-pixel place. Gauss-Newton
 * with Huber weights and a truncation minimises it over the pose (rotation
 * vector, translation), fx, fy, cx, cy, the colour lens's first
 * distortion_terms coefficients (OpenCV's k1, k2, p1, p2, k3; the rest held
 * at the start's), and one offset of all silhouettes outwards (a
 * structured-light camera widens near surfaces). A real lens matters: behind
 * the TUM fr1 Kinect's colour lens (up to 22 px at the corners), a pinhole
 * fit drags the focal length and the depth offset along the direction the
 * edges cannot tell apart, and is rejected as implausible (README "An
 * unknown colour-depth calibration"). The depth intrinsics are taken as given: the edges fix the
 * colour camera relative to them. A prior (TOptions::prior_*) keeps poorly
 * seen directions near the start: the edges hardly tell the depth offset
 * between the cameras from the focal length, nor a small rotation from a
 * shift of the principal point.
 *
 * The estimate replaces the start only when it is well determined, fits
 * better and stays plausible (TResult::accepted): the frames split into
 * TOptions::groups interleaved groups, each estimated alone from the joint
 * estimate, and the spread of where they land depth readings in the colour
 * image must stay within max_spread_px; the mean truncated edge distance
 * must drop; the estimated lens must map the image one to one (its
 * distorted radius growing along every ray out to the border); no
 * parameter may move more than max_prior_sigmas from the start; the estimate must differ from the
 * start by more than the method's own error (min_change_px); and the depth read as registered
 * already must not fit better (registered_ratio: a description that calls registered depth
 * unregistered). Otherwise the start stays, and TResult::reason says why.
 *
 * TOptions (code only; every field has its default):
 *   max_points_per_frame  3000     silhouette points kept per frame (evenly)
 *   min_jump_m            0.05 m   a discontinuity: the neighbour is farther by
 *   min_jump_ratio        0.05     at least max(min_jump_m, ratio x depth)
 *   truncate_px           8 px     a residual beyond it is an outlier (weight 0)
 *   huber_px              1.5 px   Huber threshold of the weights
 *   iterations            30       Gauss-Newton iterations at most
 *   groups                4        interleaved frame groups for the spread
 *   prior_translation_m   0.02 m   1-sigma prior on the x, y translation
 *   prior_translation_z_m 0.002 m  ... and on z (both cameras on one board:
 *                                  their optical centres at one depth)
 *   prior_rotation_deg    2 deg    1-sigma prior on each rotation axis
 *   prior_focal_ratio     0.03     1-sigma prior on fx, fy (relative)
 *   prior_principal_px    10 px    1-sigma prior on cx, cy
 *   prior_silhouette_px   2 px     1-sigma prior on the silhouettes' offset
 *   distortion_terms      5        colour distortion terms estimated: 0 (none),
 *                                  2 (k1, k2), 4 (and p1, p2) or 5 (and k3)
 *   prior_k1, prior_k2, prior_k3   0.25, 1, 1   1-sigma priors on the radial
 *   prior_tangential      0.01     and tangential coefficients (wide: a Kinect
 *                                  v1 lens reads k1 0.26, k2 -0.95, k3 1.16)
 *   max_spread_px         0.25 px  acceptance: spread of the groups at most
 *   min_change_px         0.75 px  acceptance: the estimate moves depth readings
 *                                  at least this far from the start (RMS);
 *                                  closer is within the method's own error
 *   registered_ratio      0.8      rejection: the depth read as registered
 *                                  already fits better than this times the
 *                                  start, and better than a plausible
 *                                  estimate (the reason says so)
 *   max_prior_sigmas      3        acceptance: no parameter moved further
 *                                  from the start (in prior sigmas)
 *   min_frames            4        frames with discontinuities needed
 */
#pragma once

#include <roislam/io/TSensorDescription.h>

#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace roislam::io
{
class CDepthColourCalibrator
{
 public:
  struct TOptions
  {
    std::size_t max_points_per_frame = 3000;
    double min_jump_m = 0.05;
    double min_jump_ratio = 0.05;
    double truncate_px = 8;
    double huber_px = 1.5;
    int iterations = 30;
    int groups = 4;
    double prior_translation_m = 0.02;
    double prior_translation_z_m = 0.002;
    double prior_rotation_deg = 2;
    double prior_focal_ratio = 0.03;
    double prior_principal_px = 10;
    double prior_silhouette_px = 2;
    int distortion_terms = 5;
    double prior_k1 = 0.25;
    double prior_k2 = 1.0;
    double prior_k3 = 1.0;
    double prior_tangential = 0.01;
    double max_spread_px = 0.25;
    double min_change_px = 0.75;
    double registered_ratio = 0.8;
    double max_prior_sigmas = 3;
    std::size_t min_frames = 4;
  };

  /** What estimate() found. */
  struct TResult
  {
    /** True when `sensor` holds the estimate; false: the start, unchanged. */
    bool accepted = false;
    /** Why it was (not) accepted, one line. */
    std::string reason;
    /** The description to read the frames with: the start with the estimated
     *  depth_pose_in_colour and colour fx, fy (estimate_registration then
     *  false: done) when accepted, else the start. */
    TSensorDescription sensor;
    /** The estimate itself, accepted or not. */
    mrpt::poses::CPose3D estimatedPose;
    double estimatedFx = 0, estimatedFy = 0, estimatedCx = 0, estimatedCy = 0;
    /** The colour lens (OpenCV's k1, k2, p1, p2, k3). */
    double estimatedK1 = 0, estimatedK2 = 0, estimatedP1 = 0, estimatedP2 = 0, estimatedK3 = 0;
    /** The depth silhouettes' offset from the colour edges, outwards (px). */
    double silhouetteOffsetPx = 0;
    std::size_t frames = 0, points = 0;
    /** Mean truncated edge distance (px) at the start and at the estimate. */
    double distanceStartPx = 0, distanceEstimatePx = 0;
    /** The same, reading the depth as registered already (the depth
     *  camera's pixels as the colour camera's; 0 when the grids differ). */
    double distanceRegisteredPx = 0;
    /** Spread of the group estimates where depth readings land in the
     *  colour image (px; standard deviation / sqrt(groups), RMS over a grid
     *  of readings at 1, 2 and 4 m). */
    double spreadPx = 0;
    /** RMS distance (px) between where the start and the estimate land the
     *  same readings (the grid of spreadPx). */
    double changePx = 0;

    /** One line: accepted or not, the estimate, the distances, the reason. */
    std::string summary() const;
  };

  /** Why `sensor` cannot be a start ("" when it can): registered depth, a
   *  negative focal length (a flipped axis) or a camera without a size. */
  static std::string whyNotEstimable(const TSensorDescription& sensor);

  /** `start`: the description to start from (whyNotEstimable() empty,
   *  else throws std::invalid_argument). */
  explicit CDepthColourCalibrator(const TSensorDescription& start);
  CDepthColourCalibrator(const TSensorDescription& start, const TOptions& options);

  /** Adds one frame: colour CV_8UC3 on the colour camera's grid, depth
   *  CV_32FC1 metres (0 = none) on the depth camera's grid. Throws
   *  std::invalid_argument on a wrong type or size. */
  void addFrame(const cv::Mat& colourBgr, const cv::Mat& depthMetres);
  /** Frames added that have discontinuities. */
  std::size_t frames() const { return m_frames.size(); }

  TResult estimate() const;

 private:
  struct TFrame
  {
    std::vector<cv::Point3d> points;      //!< silhouettes, depth optical frame
    std::vector<cv::Point2d> outward;     //!< each one's direction to the far side (px)
    cv::Mat nearest;                      //!< CV_32S: index of the nearest colour edge pixel
    std::vector<cv::Point2d> edgeAt;      //!< each edge's sub-pixel position
    std::vector<cv::Point2d> edgeNormal;  //!< and its unit gradient direction
  };
  struct TParams;      //!< the values estimated (defined in the .cpp)
  struct TEvaluation;  //!< how some frames fit some values

  /** The fit of `frames` at `p`: robust cost, mean truncated edge distance
   *  and, withJacobian, the normal equations (without the prior). */
  TEvaluation evaluate(
      const TParams& p, const std::vector<std::size_t>& frames, double truncate,
      bool withJacobian) const;
  /** Gauss-Newton from `p` over `frames`, under the prior around the start. */
  TParams solve(TParams p, const std::vector<std::size_t>& frames) const;
  /** Where `p` lands the reference readings in the colour image. */
  std::vector<cv::Point2d> projectReference(const TParams& p) const;
  /** TResult::spreadPx of the interleaved frame groups, each from `joint`. */
  double groupSpreadPx(const TParams& joint) const;
  /** "" when p's colour distortion maps the image one to one, else what
   *  is wrong with it. */
  std::string whereDistortionFolds(const TParams& p) const;
  /** Why the estimate `joint` (its figures in `res`) is not to be used;
   *  "" when it is. */
  std::string whyNotUsed(const TResult& res, const TParams& joint) const;

  TSensorDescription m_start;
  TOptions m_options;
  std::vector<cv::Point3d> m_reference;  //!< a grid over the depth image at 1, 2, 4 m
  std::vector<TFrame> m_frames;
};
}  // namespace roislam::io
