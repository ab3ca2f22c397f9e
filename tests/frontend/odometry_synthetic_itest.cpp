// Odometry only on the rgbd-simul sequences of the synthetic_data fixture:
// the textured room is tracked by features in every mode, the featureless
// room by depth ICP (never lost), and strict ROI mode loses the featureless
// frames as the dissertation's ROI versions did.
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <opencv2/core/types.hpp>
#include <set>
#include <tuple>

#include "OdometryRun.h"

using roislam::frontend::CRgbdOdometry;
using roislam::frontend::EFrontEndMode;
using roislam::frontend::ETrackingMethod;
using roislam::frontend::testing::runOdometry;

namespace
{
CRgbdOdometry::TOptions orb(EFrontEndMode mode)
{
  CRgbdOdometry::TOptions o;
  o.mode = mode;
  o.extractor.feature_type = roislam::features::EFeatureType::ORB;
  o.extractor.max_features = 600;
  return o;
}

/** orb(mode) with roi_extraction = flow. */
CRgbdOdometry::TOptions orbFlow(EFrontEndMode mode)
{
  auto o = orb(mode);
  o.roi_extraction = "flow";
  return o;
}

/** region grown by the detector's support m on every side, clipped to the
 *  image: the pixels a region-only extraction may read. */
cv::Rect paddedRegion(const cv::Rect& region, int m, const cv::Size& image)
{
  return cv::Rect(region.x - m, region.y - m, region.width + 2 * m, region.height + 2 * m) &
         cv::Rect(0, 0, image.width, image.height);
}
}  // namespace

TEST(OdometrySynthetic, TexturedTraditionalAndRoi)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  for (auto mode : {EFrontEndMode::Traditional, EFrontEndMode::RoiBig})
  {
    const auto s = runOdometry(dir, orb(mode));
    ASSERT_TRUE(s.ate.has_value());
    std::cout << toString(mode) << ": ATE " << *s.ate << " m, features " << s.stats.features
              << " roi " << s.stats.roiFeatures << " fallback " << s.stats.fullImageFallback
              << " icp " << s.stats.depthIcp << " cv " << s.stats.constantVelocity << "\n";
    EXPECT_EQ(s.stats.lost, 0u);
    EXPECT_EQ(s.trajectory.size(), s.results.size());
    EXPECT_LE(s.stats.constantVelocity, s.results.size() / 20);
    EXPECT_LT(*s.ate, 0.05) << toString(mode);
  }
}

TEST(OdometrySynthetic, RegionFramesDescribeOnlyTheirRegion)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  // Both modes, and the half-resolution extension with the small ROI.
  for (const auto& [mode, scale] :
       {std::pair{EFrontEndMode::RoiBig, 1.0}, std::pair{EFrontEndMode::RoiSmall, 1.0},
        std::pair{EFrontEndMode::RoiSmall, 0.5}})
  {
    SCOPED_TRACE(toString(mode) + " extension scale " + std::to_string(scale));
    auto o = orb(mode);
    o.roi_extraction = "region";
    o.roi_extension_scale = scale;
    const auto s = runOdometry(dir, o);
    ASSERT_TRUE(s.ate.has_value());
    std::map<roislam::frontend::EExtension, std::size_t> counted;
    std::size_t roiOnly = 0;
    for (const auto& r : s.results)
    {
      const auto& w = r.work;
      ++counted[w.extension];
      const cv::Size image = r.imageSize;
      if (w.extension == roislam::frontend::EExtension::None)
      {
        // ROI-only: the detector ran on the region and its margin alone, and
        // every feature lies inside the region.
        ++roiOnly;
        ASSERT_FALSE(w.region.empty()) << "frame " << r.frameIndex;
        const int m = 31;  // ORB's support (CFeatureExtractor::supportPx)
        const cv::Rect padded = paddedRegion(w.region, m, image);
        EXPECT_EQ(w.regionPixels, static_cast<std::size_t>(padded.area()));
        EXPECT_EQ(w.extensionPixels, 0u);
        EXPECT_EQ(w.extensionFeatures, 0u);
        EXPECT_EQ(r.features, w.regionFeatures);
        EXPECT_LE(w.describedFraction(image), 1.0);
        EXPECT_EQ(r.trackingFeatures, r.featuresWithDepth) << "frame " << r.frameIndex;
      }
      else
      {
        // Extended once: the region's and the extension's features are all
        // there is.
        EXPECT_EQ(r.features, w.regionFeatures + w.extensionFeatures) << "frame " << r.frameIndex;
        // Every pixel outside the region once, at the extension's
        // resolution, each of the four bands around the region with its
        // margin (ORB: 31 px at that resolution, clipped to the image).
        if (w.extension == roislam::frontend::EExtension::ExpectedKeyframe)
        {
          // Predicted to become a keyframe: the whole image, once.
          EXPECT_EQ(w.regionPixels, 0u) << "frame " << r.frameIndex;
          EXPECT_EQ(w.extensionPixels, static_cast<std::size_t>(image.area()));
        }
        else if (w.extension != roislam::frontend::EExtension::NoRoi)
        {
          const cv::Rect g = w.region;
          const double rest = image.area() - static_cast<double>(g.area());
          double bound = 0;
          for (const cv::Size band :
               {cv::Size(image.width, g.y), cv::Size(image.width, image.height - g.br().y),
                cv::Size(g.x, g.height), cv::Size(image.width - g.br().x, g.height)})
            if (band.area() > 0)
              bound += std::min(scale * image.width, scale * band.width + 2 * 31 + 2) *
                       std::min(scale * image.height, scale * band.height + 2 * 31 + 2);
          EXPECT_LE(w.extensionPixels, bound) << "frame " << r.frameIndex;
          if (scale == 1.0)
          {
            EXPECT_GE(w.extensionPixels, rest) << "frame " << r.frameIndex;
          }
        }
      }
      if (r.isNewKeyframe && r.method != ETrackingMethod::Initial)
      {
        EXPECT_NE(w.extension, roislam::frontend::EExtension::None);
      }
    }
    // The extension never describes the region again: no keypoint twice in
    // any keyframe (which stores the whole extended set).
    for (const auto& kf : s.keyframes)
    {
      std::set<std::tuple<float, float, int>> seen;
      for (const auto& k : kf.features.keypoints)
        EXPECT_TRUE(seen.insert({k.pt.x, k.pt.y, k.octave}).second) << "keyframe " << kf.id;
    }
    // Every frame counted once, by its reason, in the run's statistics.
    std::size_t total = 0;
    for (const auto& [reason, n] : s.stats.extensions)
    {
      std::cout << "  " << toString(reason) << ": " << n << "\n";
      EXPECT_EQ(n, counted[reason]) << toString(reason);
      total += n;
    }
    EXPECT_EQ(total, s.results.size());
    EXPECT_GT(roiOnly, s.results.size() / 3);
    std::cout << toString(mode) << " region: ATE " << *s.ate << " m, ROI-only frames " << roiOnly
              << " of " << s.results.size() << ", mean described fraction "
              << s.stats.describedFractionSum / s.results.size() << "\n";
    EXPECT_LT(*s.ate, 0.05);
  }
}

TEST(OdometrySynthetic, FlowFramesDescribeOnlyTheirRoi)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  // roi_extraction = flow: an ordinary frame describes its ROI (and the
  // detector's margin) only, at the image's feature density, and follows
  // the reference keyframe's anchors by optical flow; frames are extended
  // (described beyond the ROI) at most once, each reason counted. Its ROI is
  // the reference keyframe's, followed with the predicted motion: stage 1
  // runs for keyframes (whose ROI the next frames follow) and where the
  // followed ROI left the view, not on every frame.
  for (auto mode : {EFrontEndMode::RoiBig, EFrontEndMode::RoiSmall})
  {
    SCOPED_TRACE(toString(mode));
    auto o = orbFlow(mode);
    o.flow_describe_roi = "always";
    o.roi_extension_scale = 0.5;
    const auto s = runOdometry(dir, o);
    ASSERT_TRUE(s.ate.has_value());
    std::map<roislam::frontend::EExtension, std::size_t> counted;
    std::size_t roiOnly = 0, followed = 0, stageOne = 0;
    for (const auto& r : s.results)
    {
      const auto& w = r.work;
      ++counted[w.extension];
      stageOne += r.times.roi_ms > 0;
      if (r.isNewKeyframe)
      {
        EXPECT_GT(r.times.roi_ms, 0.0) << "keyframe at frame " << r.frameIndex;
      }
      const cv::Size image = r.imageSize;
      if (w.extension == roislam::frontend::EExtension::None)
      {
        ++roiOnly;
        // The region is the frame's ROI, nothing else was described.
        if (r.roi)
        {
          EXPECT_EQ(w.region, *r.roi & cv::Rect(0, 0, image.width, image.height));
          const int m = 31;  // ORB's support (CFeatureExtractor::supportPx)
          const cv::Rect padded = paddedRegion(w.region, m, image);
          EXPECT_EQ(w.regionPixels, static_cast<std::size_t>(padded.area()));
          // The image's density: the ROI's share of max_features (at least
          // min_roi_features).
          EXPECT_LE(
              static_cast<double>(w.regionFeatures),
              std::max(
                  static_cast<double>(o.min_roi_features),
                  std::ceil(600.0 * w.region.area() / image.area())));
        }
        else
          EXPECT_EQ(w.regionPixels, 0u);
        EXPECT_EQ(w.extensionPixels, 0u);
        EXPECT_EQ(w.extensionFeatures, 0u);
        EXPECT_EQ(r.features, w.regionFeatures);
        // What it tracked with: the ROI's features and the followed anchors.
        EXPECT_EQ(r.trackingFeatures, r.roiFeatures + r.flowTracks) << "frame " << r.frameIndex;
        followed += r.flowTracks > 0;
      }
      else
        EXPECT_EQ(r.features, w.regionFeatures + w.extensionFeatures) << "frame " << r.frameIndex;
      if (r.isNewKeyframe)
      {
        EXPECT_NE(w.extension, roislam::frontend::EExtension::None);
      }
    }
    // Keyframes store the whole image once, and their anchors.
    for (const auto& kf : s.keyframes)
    {
      std::set<std::tuple<float, float, int>> seen;
      for (const auto& k : kf.features.keypoints)
        EXPECT_TRUE(seen.insert({k.pt.x, k.pt.y, k.octave}).second) << "keyframe " << kf.id;
      EXPECT_GT(kf.anchorPoints.size(), 20u) << "keyframe " << kf.id;
      EXPECT_EQ(kf.anchorPoints.size(), kf.anchorPixels.size());
      EXPECT_EQ(kf.anchorPoints.size(), kf.anchorKeypoints.size());
      // flow_anchors = features: each anchor is one of its features with
      // depth (its keypoint, 3-D point and undistorted pixel).
      for (std::size_t j = 0; j < kf.anchorKeypoints.size(); ++j)
      {
        bool found = false;
        for (std::size_t i = 0; i < kf.features.keypoints.size() && !found; ++i)
          found = kf.features.keypoints[i].pt == kf.anchorKeypoints[j] &&
                  kf.points[i] == kf.anchorPoints[j] && kf.pixels[i] == kf.anchorPixels[j];
        EXPECT_TRUE(found) << "keyframe " << kf.id << " anchor " << j;
      }
      // The region its flow frames follow is its stage-1 ROI.
      if (kf.roi)
      {
        EXPECT_EQ(kf.region, *kf.roi & cv::Rect(0, 0, 640, 480)) << "keyframe " << kf.id;
      }
    }
    EXPECT_LT(stageOne, s.results.size() / 2);
    std::size_t total = 0;
    for (const auto& [reason, n] : s.stats.extensions)
    {
      EXPECT_EQ(n, counted[reason]) << toString(reason);
      total += n;
    }
    EXPECT_EQ(total, s.results.size());
    EXPECT_GT(roiOnly, s.results.size() / 2);
    EXPECT_EQ(followed, roiOnly);
    std::cout << toString(mode) << " flow: ATE " << *s.ate << " m, ROI-only frames " << roiOnly
              << " of " << s.results.size() << ", stage 1 on " << stageOne
              << ", mean described fraction " << s.stats.describedFractionSum / s.results.size()
              << "\n";
    EXPECT_LT(*s.ate, 0.05);
  }
}

TEST(OdometrySynthetic, FlowFramesDescribeTheirRoiOnlyWhenTheAnchorsAreWeak)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  // flow_describe_roi = when_weak (the default): an ordinary flow frame
  // follows the reference keyframe's anchors everywhere and describes
  // nothing; its ROI is described (and only its ROI, once) when the
  // anchors' registration is weak, and the rest of the image only when that
  // is weak too. max_roi_sigma_m = 1e-9 makes every registration weak, so
  // every frame takes both steps.
  using roislam::frontend::EExtension;
  for (const double sigma : {0.005, 1e-9})
    for (auto mode : {EFrontEndMode::RoiBig, EFrontEndMode::RoiSmall})
    {
      SCOPED_TRACE(toString(mode) + " max_roi_sigma_m " + std::to_string(sigma));
      auto o = orbFlow(mode);
      ASSERT_EQ(o.flow_describe_roi, "when_weak");
      o.max_roi_sigma_m = sigma;
      const auto s = runOdometry(dir, o);
      ASSERT_TRUE(s.ate.has_value());
      std::size_t anchorsOnly = 0, roiDescribed = 0, bothWeak = 0;
      for (const auto& r : s.results)
      {
        const auto& w = r.work;
        const cv::Rect image(0, 0, r.imageSize.width, r.imageSize.height);
        if (w.extension == EExtension::None)
        {
          EXPECT_EQ(w.extensionPixels, 0u) << "frame " << r.frameIndex;
          if (w.regionPixels == 0)
          {
            // Nothing described: the anchors alone tracked it.
            ++anchorsOnly;
            EXPECT_EQ(r.features, 0u) << "frame " << r.frameIndex;
            EXPECT_EQ(r.method, ETrackingMethod::Flow) << "frame " << r.frameIndex;
            EXPECT_EQ(r.trackingFeatures, r.flowTracks) << "frame " << r.frameIndex;
            EXPECT_GT(r.flowTracks, 0u) << "frame " << r.frameIndex;
          }
          else
          {
            ++roiDescribed;
            ASSERT_TRUE(r.roi.has_value()) << "frame " << r.frameIndex;
            EXPECT_EQ(w.region, *r.roi & image) << "frame " << r.frameIndex;
            EXPECT_EQ(r.features, w.regionFeatures) << "frame " << r.frameIndex;
            EXPECT_EQ(r.trackingFeatures, r.roiFeatures + r.flowTracks) << "frame " << r.frameIndex;
          }
        }
        else if (w.extension == EExtension::RoiWeak && r.roi && !r.isNewKeyframe)
        {
          // The ROI first, then the rest: nothing described twice.
          ++bothWeak;
          EXPECT_EQ(w.region, *r.roi & image) << "frame " << r.frameIndex;
          EXPECT_GT(w.regionPixels, 0u) << "frame " << r.frameIndex;
          EXPECT_GT(w.extensionPixels, 0u) << "frame " << r.frameIndex;
          EXPECT_EQ(r.features, w.regionFeatures + w.extensionFeatures) << "frame " << r.frameIndex;
        }
      }
      std::cout << toString(mode) << " when_weak, sigma " << sigma << ": ATE " << *s.ate
                << " m, anchors only " << anchorsOnly << ", ROI described " << roiDescribed
                << ", ROI and image " << bothWeak << " of " << s.results.size() << "\n";
      EXPECT_GE(s.stats.flow, anchorsOnly);
      if (sigma > 1e-6)
      {
        EXPECT_GT(anchorsOnly, s.results.size() / 2);
      }
      else
      {
        EXPECT_EQ(anchorsOnly, 0u);
        EXPECT_GT(bothWeak, s.results.size() / 2);
      }
      EXPECT_EQ(s.stats.lost, 0u);
      EXPECT_LT(*s.ate, 0.05);
    }
}

TEST(OdometrySynthetic, ExpectedKeyframesDescribeTheWholeImageOnce)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  // keyframe_prediction: a frame whose predicted pose meets the keyframe
  // criteria describes the whole image in one pass and tracks with it,
  // instead of its ROI and the flow first, then the rest band by band and a
  // second registration after the decision.
  for (auto mode : {EFrontEndMode::RoiBig, EFrontEndMode::RoiSmall})
  {
    SCOPED_TRACE(toString(mode));
    auto o = orbFlow(mode);
    std::map<bool, std::size_t> extendedAfter;
    for (const bool predict : {false, true})
    {
      o.keyframe_prediction = predict;
      const auto s = runOdometry(dir, o);
      ASSERT_TRUE(s.ate.has_value());
      std::size_t expected = 0, expectedKeyframes = 0, rescued = 0;
      for (const auto& r : s.results)
      {
        const auto& w = r.work;
        extendedAfter[predict] += w.extension == roislam::frontend::EExtension::Keyframe;
        if (w.extension != roislam::frontend::EExtension::ExpectedKeyframe)
          continue;
        ++expected;
        expectedKeyframes += r.isNewKeyframe;
        // The whole image, once, before tracking.
        EXPECT_EQ(w.regionPixels, 0u) << "frame " << r.frameIndex;
        EXPECT_EQ(w.regionFeatures, 0u) << "frame " << r.frameIndex;
        EXPECT_EQ(w.extensionPixels, static_cast<std::size_t>(r.imageSize.area()));
        EXPECT_EQ(r.features, w.extensionFeatures) << "frame " << r.frameIndex;
        // Tracked with every feature it described (that has depth), and
        // the followed anchors where those alone were weak
        // (rescueWithAnchors).
        EXPECT_EQ(r.trackingFeatures, r.featuresWithDepth + r.flowTracks)
            << "frame " << r.frameIndex;
        rescued += r.flowTracks > 0;
      }
      std::cout << toString(mode) << " prediction " << predict << ": ATE " << *s.ate
                << " m, keyframes " << s.keyframes.size() << ", expected " << expected
                << " (became keyframes " << expectedKeyframes << "), extended after the decision "
                << extendedAfter[predict] << ", rescued by the anchors " << rescued << "\n";
      EXPECT_LT(rescued, expected / 2 + 1);
      if (!predict)
      {
        EXPECT_EQ(expected, 0u);
        EXPECT_GT(extendedAfter[predict], 0u);
      }
      else
      {
        // The prediction is right most of the time: most keyframes are made
        // by frames that expected to be one, few expected frames are not.
        EXPECT_GT(expected, 0u);
        EXPECT_GT(2 * expectedKeyframes, expected);
        EXPECT_LT(extendedAfter[true], extendedAfter[false]);
      }
      EXPECT_LT(*s.ate, 0.05);
    }
  }
  // With the extension at half resolution its bands cost less than one
  // whole-image pass: nothing is predicted.
  auto o = orbFlow(EFrontEndMode::RoiSmall);
  o.roi_extension_scale = 0.5;
  const auto s = runOdometry(dir, o);
  for (const auto& r : s.results)
    EXPECT_NE(r.work.extension, roislam::frontend::EExtension::ExpectedKeyframe)
        << "frame " << r.frameIndex;
}

TEST(OdometrySynthetic, WeakExpectedKeyframesAreRescuedByTheAnchors)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  // An expected keyframe tracks with the whole image's features; where that
  // registration is weak (here every one: max_roi_sigma_m = 1e-9) the
  // reference keyframe's anchors, followed by flow, join them and the
  // better-determined registration is kept. With more constraints it is
  // nearly always the joint one.
  auto o = orbFlow(EFrontEndMode::RoiBig);
  o.max_roi_sigma_m = 1e-9;
  const auto s = runOdometry(dir, o);
  ASSERT_TRUE(s.ate.has_value());
  std::size_t expected = 0, rescued = 0;
  for (const auto& r : s.results)
  {
    if (r.work.extension != roislam::frontend::EExtension::ExpectedKeyframe)
      continue;
    ++expected;
    rescued += r.flowTracks > 0;
    EXPECT_EQ(r.trackingFeatures, r.featuresWithDepth + r.flowTracks) << "frame " << r.frameIndex;
    // The whole image by design, not a fallback.
    EXPECT_EQ(r.method, ETrackingMethod::Features) << "frame " << r.frameIndex;
  }
  std::cout << "weak expected keyframes: " << expected << ", rescued by the anchors " << rescued
            << ", ATE " << *s.ate << " m\n";
  EXPECT_GT(expected, 5u);
  EXPECT_GT(2 * rescued, expected);
  EXPECT_EQ(s.stats.lost, 0u);
  EXPECT_LT(*s.ate, 0.05);
}

TEST(OdometrySynthetic, FlowInlierShareMakesKeyframes)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  // keyframe_min_flow_inlier_share: a frame tracked by the anchors alone
  // becomes a keyframe when fewer of its followed anchors than this share
  // are inliers. Near 1 nearly every such frame does; 0 (default) is off.
  std::map<double, std::size_t> keyframes;
  for (const double share : {0.0, 0.999})
  {
    auto o = orbFlow(EFrontEndMode::RoiBig);
    o.keyframe_min_flow_inlier_share = share;
    const auto s = runOdometry(dir, o);
    ASSERT_TRUE(s.ate.has_value());
    keyframes[share] = s.keyframes.size();
    for (const auto& r : s.results)
      if (share > 0 && r.method == ETrackingMethod::Flow && !r.isNewKeyframe)
      {
        EXPECT_GE(static_cast<double>(r.inliers), share * static_cast<double>(r.matches))
            << "frame " << r.frameIndex;
      }
    std::cout << "flow inlier share " << share << ": keyframes " << s.keyframes.size() << ", ATE "
              << *s.ate << " m\n";
    EXPECT_LT(*s.ate, 0.05);
  }
  EXPECT_GT(keyframes[0.999], keyframes[0.0]);
}

TEST(OdometrySynthetic, WeakRoiFramesBecomeKeyframes)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  // keyframe_on_weak_roi: a frame whose ROI registration was weak (here every
  // one: max_roi_sigma_m = 1e-9) and that was therefore described on the
  // whole image becomes a keyframe, unless depth ICP carries it (over half
  // of the fused information: rendered depth often does); off, most such
  // frames do not. Every frame still tracks.
  using roislam::frontend::EExtension;
  for (auto mode : {EFrontEndMode::RoiBig, EFrontEndMode::RoiSmall})
    for (const bool on : {false, true})
    {
      SCOPED_TRACE(toString(mode) + (on ? " on" : " off"));
      auto o = orbFlow(mode);
      o.max_roi_sigma_m = 1e-9;
      o.keyframe_on_weak_roi = on;
      const auto s = runOdometry(dir, o);
      ASSERT_TRUE(s.ate.has_value());
      std::size_t weak = 0, weakKeyframes = 0, notCarried = 0, notCarriedKeyframes = 0;
      for (const auto& r : s.results)
      {
        const auto e = r.work.extension;
        if (e != EExtension::RoiWeak && e != EExtension::RoiFailed)
          continue;
        ++weak;
        weakKeyframes += r.isNewKeyframe ? 1 : 0;
        if (r.icpInformationShare > 0.5)
          continue;
        ++notCarried;
        notCarriedKeyframes += r.isNewKeyframe ? 1 : 0;
      }
      std::cout << toString(mode) << " keyframe_on_weak_roi " << on << ": weak frames " << weak
                << " (" << notCarried << " not carried by depth ICP), of them keyframes "
                << weakKeyframes << " (" << notCarriedKeyframes << "), keyframes "
                << s.keyframes.size() << ", ATE " << *s.ate << " m\n";
      EXPECT_GT(weak, 5u);
      if (on)
      {
        EXPECT_GT(notCarried, 5u);
        EXPECT_EQ(notCarriedKeyframes, notCarried);
      }
      else
      {
        EXPECT_LT(2 * weakKeyframes, weak);
      }
      EXPECT_EQ(s.stats.lost, 0u);
      EXPECT_LT(*s.ate, 0.05);
    }
}

TEST(OdometrySynthetic, RollingShutterCorrectionRecoversTheSkewedFrames)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  // The fixture's camera reads its rows out over 25 ms (rgbd-simul's
  // Kinect-like default) while turning at up to 55 deg/s. Odometry alone (no
  // graph to average errors away): the correction with the true readout must
  // beat the global-shutter model clearly, in every front-end mode.
  for (auto mode : {EFrontEndMode::Traditional, EFrontEndMode::RoiBig})
  {
    auto o = orb(mode);
    o.rolling_shutter_ms = 0;
    const auto global = runOdometry(dir, o);
    o.rolling_shutter_ms = 25;
    const auto corrected = runOdometry(dir, o);
    ASSERT_TRUE(global.ate && corrected.ate);
    std::cout << toString(mode) << ": odometry ATE global shutter " << *global.ate
              << " m, rolling shutter 25 ms " << *corrected.ate << " m\n";
    EXPECT_LT(*corrected.ate, 0.8 * *global.ate) << toString(mode);
    EXPECT_EQ(corrected.stats.lost, 0u);
  }
}

TEST(OdometrySynthetic, WeakRoiRegistrationsFallBackToTheWholeImage)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  // Two gates, each set so that no ROI registration can pass it: more
  // inliers than a ROI can have, or a pose determined better than any
  // registration can be. Every frame whose ROI holds only part of the image's
  // features is then tracked on the whole image. With both gates off the ROI
  // tracks most of those frames itself.
  struct TCase
  {
    const char* name;
    int minInliers;
    double maxSigmaM;
    bool expectFallback;
  };
  for (const TCase c :
       {TCase{"min_roi_inliers", 100000, 0.0, true}, TCase{"max_roi_sigma_m", 0, 1e-9, true},
        TCase{"off", 0, 0.0, false}})
  {
    SCOPED_TRACE(c.name);
    auto o = orb(EFrontEndMode::RoiBig);
    o.min_roi_inliers = c.minInliers;
    o.max_roi_sigma_m = c.maxSigmaM;
    const auto s = runOdometry(dir, o);
    std::size_t partial = 0, roiTracked = 0;
    for (std::size_t k = 1; k < s.results.size(); ++k)
    {
      const auto& r = s.results[k];
      if (r.method != ETrackingMethod::RoiFeatures &&
          r.method != ETrackingMethod::FullImageFallback)
        continue;
      if (r.roiFeatures < r.featuresWithDepth &&
          static_cast<int>(r.roiFeatures) >= o.min_roi_features)
      {
        ++partial;
        if (r.method == ETrackingMethod::RoiFeatures)
          ++roiTracked;
        if (c.expectFallback)
        {
          EXPECT_EQ(r.method, ETrackingMethod::FullImageFallback) << "frame " << k;
          EXPECT_EQ(r.trackingFeatures, r.featuresWithDepth) << "frame " << k;
        }
      }
    }
    EXPECT_GT(partial, s.results.size() / 2);
    if (!c.expectFallback)
    {
      EXPECT_GT(roiTracked, partial / 2);
    }
    EXPECT_EQ(s.stats.lost, 0u);
    ASSERT_TRUE(s.ate.has_value());
    EXPECT_LT(*s.ate, 0.05);
  }
}

TEST(OdometrySynthetic, FeaturelessTrackedFromDepth)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "featureless");
  // ROI mode: no ROI anywhere; the few features on face borders or depth ICP
  // must carry every frame.
  const auto s = runOdometry(dir, orb(EFrontEndMode::RoiBig));
  ASSERT_TRUE(s.ate.has_value());
  std::cout << "featureless roi_big: ATE " << *s.ate << " m, fallback " << s.stats.fullImageFallback
            << " icp " << s.stats.depthIcp << " cv " << s.stats.constantVelocity << "\n";
  EXPECT_EQ(s.stats.lost, 0u);
  EXPECT_EQ(s.trajectory.size(), s.results.size());  // every frame has a pose
  EXPECT_EQ(s.stats.roiFeatures, 0u);
  EXPECT_LE(s.stats.constantVelocity, s.results.size() / 20);
  EXPECT_LT(*s.ate, 0.06);

  // Depth alone: features disabled by an unreachable inlier count.
  auto o = orb(EFrontEndMode::RoiBig);
  o.min_inliers = 100000;
  const auto d = runOdometry(dir, o);
  ASSERT_TRUE(d.ate.has_value());
  std::cout << "featureless depth only: ATE " << *d.ate << " m, icp " << d.stats.depthIcp << " cv "
            << d.stats.constantVelocity << "\n";
  EXPECT_EQ(d.stats.depthIcp, d.results.size() - 1);
  EXPECT_EQ(d.trajectory.size(), d.results.size());
  EXPECT_LT(*d.ate, 0.05);
}

TEST(OdometrySynthetic, FeaturelessRegionModeIsNeverLost)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "featureless");
  // Describing regions only changes nothing here: without a ROI every frame
  // describes the whole image (counted as no_roi), then depth ICP carries it.
  for (auto mode : {EFrontEndMode::RoiBig, EFrontEndMode::RoiSmall})
  {
    auto o = orb(mode);
    o.roi_extraction = "region";
    o.roi_extension_scale = 0.5;
    const auto s = runOdometry(dir, o);
    ASSERT_TRUE(s.ate.has_value());
    EXPECT_EQ(s.stats.lost, 0u) << toString(mode);
    EXPECT_EQ(s.trajectory.size(), s.results.size());
    EXPECT_LE(s.stats.constantVelocity, s.results.size() / 20);
    EXPECT_LT(*s.ate, 0.06) << toString(mode);
  }
}

TEST(OdometrySynthetic, FeaturelessFlowModeIsNeverLost)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "featureless");
  // Without a ROI a flow frame describes nothing; the anchors of white
  // faces are few, and depth ICP carries the frames they cannot.
  for (auto mode : {EFrontEndMode::RoiBig, EFrontEndMode::RoiSmall})
  {
    auto o = orbFlow(mode);
    const auto s = runOdometry(dir, o);
    ASSERT_TRUE(s.ate.has_value());
    EXPECT_EQ(s.stats.lost, 0u) << toString(mode);
    EXPECT_EQ(s.trajectory.size(), s.results.size());
    EXPECT_LE(s.stats.constantVelocity, s.results.size() / 20);
    EXPECT_LT(*s.ate, 0.06) << toString(mode);
  }
}

TEST(OdometrySynthetic, FeaturelessStrictRoiIsLost)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "featureless");
  auto o = orb(EFrontEndMode::RoiBig);
  o.strict_roi = true;
  const auto s = runOdometry(dir, o);
  // No ROI features on uniform faces: (almost) every frame is lost.
  EXPECT_GE(s.stats.lost, s.results.size() * 9 / 10);
  EXPECT_EQ(s.stats.depthIcp + s.stats.constantVelocity + s.stats.fullImageFallback, 0u);
}
