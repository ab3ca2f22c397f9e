/* Options of the front end (CRgbdOdometry::TOptions, CRgbdOdometry.h).
 *
 * ini section "FrontEnd" (TOptions), units in brackets:
 *  - mode                     traditional|roi_small|roi_big|roi (default traditional);
 *                             roi_small/roi_big set the [RoiDetector] preset to
 *                             small/big, roi uses [RoiDetector] as written
 *  - strict_roi               bool (false), see CRgbdOdometry.h
 *  - min_roi_features         int >= 3 (20): fewer ROI features with depth ->
 *                             full-image fallback (or Lost if strict)
 *  - min_roi_inliers          int >= 0 (0 = off): a ROI registration with
 *                             fewer inliers is replaced by a whole-image one
 *                             when that registers (counted as fallback)
 *  - max_roi_sigma_m          [m] >= 0 (0.005; 0 = off): a ROI registration
 *                             whose worst-determined translation direction
 *                             has a larger 1-sigma (PoseUncertainty.h) is
 *                             replaced by a whole-image one when that
 *                             registers (counted as fallback). Features
 *                             crowded in a small ROI leave a rotation/
 *                             translation ambiguity that many inliers do not
 *                             reveal; 5 mm keeps a frame's 3-sigma within the
 *                             1.5 cm ATE aimed at
 *  - max_roi_sigma_deg        [deg] >= 0 (0 = off): the same on rotation
 *  - roi_feature_cap          image|roi (image): ROI modes, what
 *                             [FeatureExtractor] max_features caps. image: the
 *                             N strongest of the whole image, the ROI uses
 *                             those inside it (cheapest). roi: every detection
 *                             is described once, then the N strongest of the
 *                             image plus the N strongest inside the ROI are
 *                             kept: the dissertation's "N features in the ROI"
 *                             (it matters with small N, Test 3's 50).
 *  - roi_extraction           flow|region|image (image): non-strict ROI modes,
 *                             where stage 2 runs. flow: an ordinary frame
 *                             describes its ROI only (at the image's feature
 *                             density: max_features x the ROI's share of the
 *                             image, at least min_roi_features), a frame
 *                             without a ROI nothing; the rest of the view
 *                             comes from the reference keyframe's anchors
 *                             (points with depth a 21-px window apart,
 *                             chosen when the keyframe is made: flow_anchors)
 *                             followed by pyramidal Lucas-Kanade optical flow
 *                             from where the predicted motion puts them; they
 *                             join the ROI's matches as known pairs in one
 *                             RANSAC and refinement (FlowTracking.h). A frame
 *                             is still extended (at most once) when its
 *                             registration fails or is weak, or it becomes a
 *                             keyframe; keyframes describe the whole image as
 *                             in region mode. Needs keyframe_full_features.
 *                             With flow_describe_roi = when_weak (default)
 *                             the ROI itself is described only when the
 *                             anchors, followed everywhere, leave the pose
 *                             undetermined (below).
 *                             region: only in the
 *                             tracking region (the ROI grown as below, plus
 *                             the detector's support margin), extended to the
 *                             rest of the image lazily, at most once, when the
 *                             frame needs it (no ROI, too few region
 *                             features, its registration fails or is weak,
 *                             it becomes a keyframe): so the work scales with
 *                             the region, not the image (TDescribedWork).
 *                             The region gets max_features, the rest of the
 *                             image max_features x its share of the image.
 *                             image: the whole image once, the ROI selecting
 *                             its subset (strict_roi always works so). image
 *                             stays the default until region is as accurate:
 *                             with roi_extension_scale = 0.5 it is within 1.10
 *                             x traditional's ATE in 2 of 6 runs on fr1/rpy
 *                             and none on fr1/xyz (README "ROI that pays")
 *  - flow_describe_roi        always|when_weak (when_weak): roi_extraction =
 *                             flow, when an ordinary frame describes its ROI.
 *                             always: every frame, and the anchors are
 *                             followed outside it only. when_weak: the
 *                             anchors are followed everywhere first, and the
 *                             ROI is described (and registered with them)
 *                             only when their registration fails or is weak
 *                             (min_roi_inliers, max_roi_sigma_m/_deg), then
 *                             the rest of the image as before. An ordinary
 *                             frame's ROI features serve its tracking only
 *                             (the back end's landmarks are the keyframes'
 *                             ROIs), and the anchors track as well as they
 *                             do: ATE within x1.10 of always's on average
 *                             over fr1 runs, front end 2-4x cheaper (README
 *                             "ROI that pays")
 *  - flow_anchors             features|corners (features): roi_extraction =
 *                             flow, a keyframe's anchors. features: its own
 *                             described features with depth, strongest
 *                             first, a window of the tracked image apart (no
 *                             detection of their own; fewer anchors, each a
 *                             strong corner). corners: Shi-Tomasi corners
 *                             found for the purpose at half resolution, a
 *                             window apart (about 1 ms a keyframe at 640 x
 *                             480). README "Anchors from the keyframe's
 *                             features"
 *  - roi_min_area_fraction    [0, 1] (0.15): the tracking region is the ROI
 *                             grown about its centre to at least this share
 *                             of the image ...
 *  - roi_min_aspect           [0, 1] (0.5): ... and to a short side of at
 *                             least this share of its long side: the
 *                             dissertation's largest component is often a
 *                             thin strip (180 x 36 px on fr1), whose features
 *                             leave the pose poorly determined across it
 *  - roi_extension_scale      [0.25, 1] (1): roi_extraction = region, the
 *                             resolution (share of the image's) at which the
 *                             extension describes the rest of the image. The
 *                             frames track with the region's full-resolution
 *                             features; the rest serves keyframe edges, loop
 *                             closures and fallbacks, and at 0.5 costs a
 *                             quarter (SIFT, ORB, SURF scale with the pixels)
 *  - feature_resolution       full|auto (full): the resolution stage 2
 *                             detects and describes features at. full: the
 *                             camera's. auto: the image halved until it is
 *                             under 1280 px wide (the optical flow's rule,
 *                             FlowTracking.h), keypoints coming back in the
 *                             camera's pixels: 640 x 480 and 960 x 540
 *                             cameras keep theirs, a 1920 x 1080 one is
 *                             described at 960 x 540 for a quarter of the
 *                             cost, and a less precise trajectory (README
 *                             "Cameras wider than 1280 px": front end 1.7-4x
 *                             cheaper, ATE 1.7x on rgbd-simul 1080p / 720p)
 *  - min_inliers              int >= 3 (15): fewer inliers -> features failed
 *  - keyframe_policy          motion|overlap (motion): when a frame becomes a
 *                             keyframe and which keyframe it is tracked against.
 *                             motion: beyond keyframe_translation_m or
 *                             keyframe_rotation_deg from the last keyframe, or
 *                             below keyframe_min_inliers, or registered only
 *                             against an older keyframe; every frame is tracked
 *                             against the last keyframe first. overlap: each
 *                             frame is tracked against the newest keyframe
 *                             whose view overlaps its predicted view by at
 *                             least keyframe_min_overlap (and lies within the
 *                             motion bounds below), else the best-overlapping
 *                             one wherever it was made (a revisit re-uses the
 *                             keyframes made there; a keyframe without an ICP
 *                             map is accepted only when its registration needs
 *                             no depth refinement, icp_refine_sigma_m, and has
 *                             keyframe_min_inliers), and becomes
 *                             a keyframe when its view overlap with that
 *                             reference falls below keyframe_min_overlap or
 *                             its inliers below keyframe_min_inliers; the
 *                             motion thresholds, when > 0, stay upper bounds
 *                             (measured from the reference keyframe)
 *  - keyframe_place_limit     int >= 0 (8; 0 = none): keyframe_policy = motion,
 *                             the most keyframes a place may have, a place
 *                             being the keyframes within keyframe_translation_m
 *                             and keyframe_rotation_deg of the frame's
 *                             predicted pose. Where it has that many, the
 *                             frame is tracked against the nearest of them
 *                             (an old keyframe is accepted as for the overlap
 *                             policy) and becomes a keyframe only beyond the
 *                             motion thresholds from it or below
 *                             keyframe_min_inliers. New ground and the first
 *                             few revisits are mapped as with no limit, so a
 *                             place seen from several passes keeps several
 *                             views (edges, loop closures); a long run that
 *                             replays the same places stops adding keyframes
 *                             there, and the map, memory and the back end's
 *                             cost stop growing (tests/graphslam/soak_slowtest).
 *                             8 is more views than the shared fr1 excerpts
 *                             give any place (their results are those of no
 *                             limit; 3 and 5 cost up to 9 % ATE there), and
 *                             bounds the soak's map (README "Soak")
 *  - keyframe_min_overlap     [0, 1) (0.5): keyframe_policy = overlap, the
 *                             share of the reference keyframe's feature points
 *                             the frame's view must still contain (projected
 *                             with the frame's pose, in front, within the
 *                             depth range, inside the image; KeyframeOverlap.h).
 *                             0.5: consecutive keyframes share half a view, so
 *                             every part of the scene the camera sweeps over
 *                             is seen by 1 / (1 - 0.5) = 2 keyframes, the
 *                             fewest that still give each place a second view
 *                             for edges and loop closures
 *  - keyframe_translation_m   [m] (0.10): new keyframe beyond this distance;
 *                             > 0 with keyframe_policy = motion, >= 0 (0 = no
 *                             bound) with overlap
 *  - keyframe_rotation_deg    [deg] (10): ... or beyond this rotation angle
 *                             (> 0, or >= 0 with overlap, as above)
 *  - keyframe_min_inliers     int >= 0 (20): ... or when inliers drop below
 *                             this where the keyframe could give this many:
 *                             once a frame registered against it with this
 *                             many, by its described features or by
 *                             following its anchors (or it is the map's
 *                             first). A count never reached says nothing of
 *                             wear: a featureless room's shading edges give
 *                             every frame fewer, and a keyframe's 20-30
 *                             anchors there keep 18-25 of them
 *  - keyframe_min_inlier_share [0, 1) (0 = off): ... or when a frame's
 *                             feature inliers fall below this share of the
 *                             most any frame had against the same keyframe
 *                             (a registration wearing out: fast motion,
 *                             blur; a share, so the same for every detector
 *                             and scene). Off by default: 0.5 makes fr1/rpy
 *                             more accurate in every mode but traditional
 *                             the most, so that big ROI SURF no longer stays
 *                             within 1.10x of it (README "Previous-frame
 *                             bridge and a keyframe share")
 *  - keyframe_min_flow_inlier_share [0, 1) (0 = off): roi_extraction = flow:
 *                             ... or when a frame tracked by the anchors
 *                             alone has fewer RANSAC inliers than this share
 *                             of its followed anchors (their pairs are
 *                             known, so the share says how much of the
 *                             keyframe's view still moves as one with the
 *                             frame). Off by default: on the fr1 excerpts
 *                             0.4 / 0.5 / 0.6 make 4 / 10 / 19 % more
 *                             keyframes on fr1/rpy, whose ATE improves, and
 *                             fr1/xyz's moves by -5..+6 % (README "ROI that
 *                             pays")
 *  - keyframe_on_weak_roi     bool (false): ROI modes: ... or when the
 *                             frame's ROI registration was weak or failed
 *                             (EExtension::RoiWeak / RoiFailed) and the
 *                             frame still registered: its keyframe's view
 *                             is wearing out (the ROI analogue of
 *                             keyframe_min_inlier_share, judged by the ROI's
 *                             own weak-registration test: min_roi_inliers,
 *                             max_roi_sigma_m / _deg, no threshold of its
 *                             own), and the frame is described on the
 *                             whole image already, so the keyframe costs no
 *                             second description; not where depth ICP
 *                             carries the frame (over half the fused
 *                             information, or the colour check sided with
 *                             it: the ROI then fails for want of texture),
 *                             nor where the reference keyframe found no ROI
 *                             (a region it never had cannot wear out).
 *                             The shipped ROI configs turn it
 *                             on with bridge_previous_frame (README "A
 *                             keyframe where the ROI weakens", "Keyframes
 *                             where the features never were")
 *  - recent_keyframes         int >= 0 (3): older keyframes (besides the
 *                             reference) tried for tracking fallback and for
 *                             new-keyframe constraints
 *  - ransac_threshold_m       [m] > 0 (0.03): 3-D inlier distance of RANSAC
 *  - ransac_max_iterations    int >= 1 (200), adaptive (confidence 0.995)
 *  - refine_iterations        int >= 0 (10): Gauss-Newton iterations on inliers
 *  - reprojection_threshold_px [px] > 0 (3.0): inlier gate after refinement
 *                             for a keypoint of 1 px noise: each pair's gate
 *                             is this times its own sigma (pixel_sigma_px
 *                             below), i.e. 3 sigmas (chi-square with 2
 *                             degrees of freedom: 0.99 within 3.03)
 *  - pixel_sigma_px           [px] >= 0 (0): keypoint noise at the finest
 *                             detection scale, per image axis; 0 = the
 *                             detector's own (features::finestScaleSigmaPx:
 *                             ORB 0.72, SURF 0.46, SIFT 0.31). The camera's
 *                             shares (keypoint_sigma_px and the keypoint's
 *                             image speed x keypoint_time_sigma_ms below)
 *                             add to it in quadrature; each pair's inlier gate is
 *                             reprojection_threshold_px x its sigma
 *  - scale_aware_weights     bool (true): the detector's share grows with the
 *                             detection size (ORB: size/31; SIFT/SURF: size /
 *                             the smallest size among the pairs); false: one
 *                             sigma for every pyramid level (README "Trusting
 *                             ICP beyond its model": with per-detector floors
 *                             it made ORB worse, 16.24 -> 20.73 mm over 8 runs)
 *  - min_depth_m, max_depth_m [m] (0.3, 4.0): depth range used for features
 *  - depth_discontinuity_m    [m] >= 0 (0.05): skip keypoints whose 3x3 depth
 *                             neighbourhood spans more than this * depth (0 = off)
 *  - rolling_shutter_ms       [ms] in [-1000, 1000] (0 = global shutter): time
 *                             the colour camera takes to read its rows out,
 *                             top to bottom; negative: bottom to top (a camera
 *                             mounted upside down, its images turned in
 *                             software; a sequence played backwards). Each keypoint's point is
 * carried to the middle row's time with the velocity of the last motion, then, once registered,
 * with the one measured since the last frame, and the registration is refined again on the same
 *                             matches (FeatureLifting.h). A camera fact:
 *                             roi-graphslam sets it from the sensor description
 *                             (io::TSensorDescription; presets fr1/fr2/fr3: 25,
 *                             fr1/rpy, 9 runs: mean ATE 0.0265 m at 0, 0.0119 m
 *                             at 25); a value in [FrontEnd] overrides that
 *  - depth_time_correction    bool (false): a depth image stamped dt seconds
 *                             after its colour image (TRGBDFrame::depthTimestamp
 *                             minus timestamp; a Kinect v1 streams them
 *                             unsynchronised, up to half a frame apart: fr1/xyz
 *                             -12 to -17 ms) saw the scene from where the
 *                             camera was then. Each keypoint's depth is read
 *                             where its point was at the depth's time and
 *                             carried back to the colour's time with the
 *                             velocity of the last motion, as for the rolling
 *                             shutter (RollingShutter.h). No constant: the
 *                             offset is estimated from the frames' own stamps
 *                             (DepthTimeOffset.h; none for a rawlog, whose
 *                             observation has one stamp). Off: measured
 *                             better on fr1/xyz, mixed on fr1/rpy with ORB
 *                             (README "Depth taken at another time")
 *  - icp_fallback             bool (true): depth ICP when features fail
 *                             (after bridge_previous_frame)
 *  - bridge_previous_frame    bool (false): a frame whose features no longer
 *                             register against the keyframe the previous
 *                             frame tracked is registered against that
 *                             previous frame instead, and the two
 *                             registrations chained (their covariances
 *                             added): for the frame's pose before depth ICP
 *                             or constant velocity, and for the keyframe
 *                             edge from that keyframe, which would otherwise
 *                             hang on one edge. Not in strict_roi. Off in
 *                             the library; the shipped configs turn it on.
 *                             Alone it mends traditional mode's failures on
 *                             fr1/rpy, which the ROI modes' optical flow
 *                             rarely has, so they fall behind it (README
 *                             "Previous-frame bridge and a keyframe share");
 *                             with keyframe_on_weak_roi they keep up (README
 *                             "A keyframe where the ROI weakens"). With
 *                             icp_fallback the chain competes with depth
 *                             ICP: the better determined is kept, ICP's
 *                             covariance scaled by what its disagreement
 *                             with the features measured
 *  - icp_refine_sigma_m       [m] >= 0 (0.01; 0 = no depth refinement at
 *                             all): a feature registration whose worst
 *                             translation 1-sigma (PoseUncertainty.h)
 *                             exceeds this is combined (information-
 *                             weighted) with depth ICP against the same
 *                             keyframe, started from it
 *  - icp_fusion               weak | measured (measured): which feature
 *                             registrations depth ICP joins. weak: those
 *                             beyond icp_refine_sigma_m, with ICP's modelled
 *                             information. measured: the well-determined
 *                             ones too, with that information divided by the
 *                             scale the last 30 frames' disagreement of ICP
 *                             and features asks for (IcpConsistency.h: down
 *                             to 1/25, every pair independent, where ICP is
 *                             better than its model, rendered depth; until
 *                             10 frames were compared, the well-determined
 *                             ones at an unverified ICP's scale, 4; no
 *                             fusion where no scale explains it). A
 *                             well-determined registration is not fused
 *                             when its own disagreement is beyond
 *                             chi-square's 0.99 quantile at that scale, nor
 *                             while ICP's share is below icp_min_share;
 *                             beyond that quantile at a measured scale, the
 *                             better determined of the two stands (ICP's
 *                             estimate replaces the features' where it is
 *                             better determined). Where the scale says
 *                             ICP's error is mostly bias (k >= 12: the fr1
 *                             Kinect, k 10-140), a well-determined
 *                             registration's ICP pairs a quarter of the
 *                             cells (every other one of every other row),
 *                             which keeps >= 80 % of its information at a
 *                             quarter of the work (StageRefine.cpp). Where
 *                             the two disagree beyond their claims (ICP's
 *                             at its least), the colour image decides which
 *                             is wrong (PhotometricCheck.h); where it sides
 *                             with ICP, ICP's estimate replaces the
 *                             features' and the disagreement is not booked
 *                             against ICP (a featureless room); off with
 *                             icp_colour_check
 *  - icp_colour_check         bool (true): measured fusion asks the colour
 *                             image where features and ICP disagree (above)
 *  - icp_min_share            double >= 0 (0.1): measured fusion runs ICP on
 *                             every frame while the median of ICP's scaled
 *                             information relative to the features'
 *                             (tr(Sf Hicp) / 6 / scale) is at least this
 *                             (0.1: the fused pose's variance 9 % lower);
 *                             below it only as a probe, to update the
 *                             scale: icp_probe_interval registrations after
 *                             the last ICP (a constant interval, so that the
 *                             30 comparisons the scale is measured over span
 *                             a bounded stretch of the run: StageRefine.cpp)
 *  - icp_probe_interval       int >= 1 (10)
 *  - icp_decimation           int >= 1 (4): ICP uses every n-th pixel/row
 *                             (of an image under 1280 px wide; n x 2 per
 *                             halving of a wider one, as the flow and the
 *                             features: FlowTracking.h flowShift)
 *  - icp_max_iterations       int >= 1 (15)
 *  - icp_converged_step_sigma double >= 0 (0.2): ICP has converged once a
 *                             Gauss-Newton step moves the pose by less than
 *                             this fraction of the standard deviation its own
 *                             information claims (after one iteration with
 *                             the tight gate). 0: only when the step is
 *                             below 10 um and 1e-5 rad, which projective
 *                             association rarely reaches (fr1/rpy: half the
 *                             alignments ran all 15 iterations). 0.2 since
 *                             stop 37, whose ICP claims 4x the information
 *                             (CDepthIcp::kIndependentPairShare): the same
 *                             step in metres as 0.1 before, so the same
 *                             iterations (0.1 now: 25-60 % more ICP time)
 *  - icp_max_distance_m       [m] > 0 (0.10): correspondence gate
 *  - icp_min_pairs            int >= 6 (500): fewer -> ICP failed
 *  - constant_velocity_information_scale  double > 0 (1e-2): information of a
 *                             constant-velocity keyframe edge = this * identity
 *                             (0.01 -> sigma 10 m / 10 rad: it only links the graph)
 *  - keyframe_full_features   bool (true): a keyframe stores the features of
 *                             the whole image (with depth); a ROI-mode frame's
 *                             ROI features are matched against them. false
 *                             stores only the ROI subset (ROI-to-ROI matching,
 *                             the dissertation's way; measured far less robust)
 *  - keyframe_full_registration  bool (true): non-strict ROI modes compute a
 *                             new keyframe's graph edges (to its reference and
 *                             the recent keyframes) from the whole image's
 *                             features, which it stores anyway; the ROI's
 *                             features track every frame in between.
 *  - keyframe_prediction      bool (true): roi_extraction = region or flow: a
 *                             frame whose predicted pose (constant velocity)
 *                             already meets the keyframe criteria describes
 *                             the whole image at once and tracks with it, as
 *                             a traditional frame does (extension
 *                             "expected_keyframe"), instead of its region and
 *                             flow first, then the rest band by band and a
 *                             second registration once it has become one: one
 *                             detection pass instead of up to five, one
 *                             registration instead of two. A wrong prediction
 *                             costs one whole-image frame; a missed one, the
 *                             extension after the decision. Only with
 *                             roi_extension_scale = 1 (a lower resolution's
 *                             bands cost less than the image). Measured:
 *                             README "ROI that pays"
 * Sub-component sections: [RoiDetector] (CRoiDetector::TOptions),
 * [FeatureExtractor] (CFeatureExtractor::TOptions), [FeatureMatcher]
 * (CFeatureMatcher::TOptions; here brute_force by default). A bad value
 * throws std::invalid_argument "[section] key: why".
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <roislam/features/CFeatureExtractor.h>
#include <roislam/io/TSensorDescription.h>
#include <roislam/matching/CFeatureMatcher.h>
#include <roislam/roi/CRoiDetector.h>

#include <string>

namespace roislam::frontend
{
enum class EFrontEndMode
{
  Traditional,
  RoiSmall,
  RoiBig,
  /** ROI with the [RoiDetector] options exactly as configured. */
  Roi
};
/** "traditional" | "roi_small" | "roi_big" | "roi"; throws std::invalid_argument. */
EFrontEndMode frontEndModeFromString(const std::string& s);
std::string toString(EFrontEndMode m);
inline matching::CFeatureMatcher::TOptions bruteForceMatcher()
{
  matching::CFeatureMatcher::TOptions o;
  o.matcher = matching::EMatcherType::BRUTE_FORCE;
  return o;
}

inline bool isRoiMode(EFrontEndMode m)
{
  return m != EFrontEndMode::Traditional;
}

struct TRgbdOdometryOptions : public mrpt::config::CLoadableOptions
{
  EFrontEndMode mode = EFrontEndMode::Traditional;
  bool strict_roi = false;
  int min_roi_features = 20;
  int min_roi_inliers = 0;
  double max_roi_sigma_m = 0.005;
  double max_roi_sigma_deg = 0;
  std::string roi_feature_cap = "image";
  std::string roi_extraction = "image";
  std::string flow_describe_roi = "when_weak";
  std::string flow_anchors = "features";
  double roi_min_area_fraction = 0.15;
  double roi_min_aspect = 0.5;
  double roi_extension_scale = 1.0;
  std::string feature_resolution = "full";
  int min_inliers = 15;
  double keyframe_translation_m = 0.10;
  double keyframe_rotation_deg = 10.0;
  int keyframe_min_inliers = 20;
  double keyframe_min_inlier_share = 0;
  double keyframe_min_flow_inlier_share = 0;
  bool keyframe_on_weak_roi = false;
  std::string keyframe_policy = "motion";
  double keyframe_min_overlap = 0.5;
  int keyframe_place_limit = 8;
  int recent_keyframes = 3;
  double ransac_threshold_m = 0.03;
  int ransac_max_iterations = 200;
  int refine_iterations = 10;
  double reprojection_threshold_px = 3.0;
  double pixel_sigma_px = 0;
  bool scale_aware_weights = true;
  double min_depth_m = 0.3;
  double max_depth_m = 4.0;
  double depth_discontinuity_m = 0.05;
  double rolling_shutter_ms = 0;
  bool icp_fallback = true;
  bool bridge_previous_frame = false;
  double icp_refine_sigma_m = 0.01;
  std::string icp_fusion = "measured";
  double icp_min_share = 0.1;
  bool icp_colour_check = true;
  int icp_probe_interval = 10;
  int icp_decimation = 4;
  int icp_max_iterations = 15;
  double icp_converged_step_sigma = 0.2;
  double icp_max_distance_m = 0.10;
  int icp_min_pairs = 500;
  double constant_velocity_information_scale = 1e-2;
  bool keyframe_full_features = true;
  bool keyframe_full_registration = true;
  bool keyframe_prediction = true;
  bool depth_time_correction = false;

  /** The sensor's depth-noise model (not an ini key: a camera fact, set
   *  from the sensor description by whoever opens the source; default the
   *  Kinect v1's). Weighs the estimator's edge information. */
  io::TSensorDescription::TDepthNoise depth_noise;
  /** The sensor's per-image keypoint shift, px (not an ini key: a camera
   *  fact, TSensorDescription::common_pixel_sigma_px). Widens the
   *  estimator's edge information along what such a shift moves. */
  double common_pixel_sigma_px = 0;
  /** The camera's own noise of each keypoint, px per axis (not an ini key: a
   *  camera fact, TSensorDescription::keypoint_sigma_px): what blur,
   *  compression and timing add to the detector's share, whatever the
   *  detection scale; added in quadrature. */
  double keypoint_sigma_px = 0;
  /** The uncertainty of the time each keypoint is seen at, ms (not an ini
   *  key: a camera fact, TSensorDescription::keypoint_time_sigma_ms). Each
   *  keypoint's image speed (the velocity its frame was lifted with,
   *  TKeyframe::angularRate and linearRate, at its point) times it adds to
   *  its noise in quadrature. 0: no such term. */
  double keypoint_time_sigma_ms = 0;

  roi::CRoiDetector::TOptions roi;
  features::CFeatureExtractor::TOptions extractor;
  /** Brute force by default (unlike CFeatureMatcher's FLANN): at a few
   *  hundred features per set exact search is the faster one here. */
  matching::CFeatureMatcher::TOptions matcher = bruteForceMatcher();

  /** Reads `section` (normally "FrontEnd") and the sub-component sections
   *  [RoiDetector], [FeatureExtractor], [FeatureMatcher]. */
  void loadFromConfigFile(
      const mrpt::config::CConfigFileBase& source, const std::string& section) override;
  void saveToConfigFile(
      mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  /** Throws std::invalid_argument "[<section>] key: why" on a bad value
   *  (loadFromConfigFile() names the section it read: roi-graphslam-engine
   *  reads these keys from [NodeRegistrationDeciderParameters]). */
  void validate(const std::string& section = "FrontEnd") const;
};
}  // namespace roislam::frontend
