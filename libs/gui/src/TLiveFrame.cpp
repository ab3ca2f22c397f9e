#include "roislam/gui/TLiveFrame.h"

#include <algorithm>

namespace roislam::gui
{
namespace
{
/** OpenCV-allocated images are reference-counted and the pipeline never
 *  writes into a decoded frame again, so sharing is safe; an image wrapping
 *  someone else's buffer is copied. */
cv::Mat shareOrCopy(const cv::Mat& m)
{
  return m.u != nullptr ? m : m.clone();
}

TKeyframeCloud decimatedCloud(const mrpt::maps::CColouredPointsMap& map, std::size_t maxPoints)
{
  TKeyframeCloud cloud;
  const std::size_t n = map.size();
  const std::size_t step =
      std::max<std::size_t>(1, (n + maxPoints - 1) / std::max<std::size_t>(1, maxPoints));
  cloud.reserve(n / step + 1);
  for (std::size_t i = 0; i < n; i += step)
  {
    float x, y, z, r, g, b;
    map.getPointRGB(i, x, y, z, r, g, b);
    const auto u8 = [](float c)
    { return static_cast<uint8_t>(std::clamp(c, 0.f, 1.f) * 255.f + 0.5f); };
    cloud.emplace_back(x, y, z, u8(r), u8(g), u8(b));
  }
  return cloud;
}
}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> loopPairs(const graphslam::CSlamContext& context)
{
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (const auto& lc : context.loopClosures())
    pairs.emplace_back(lc.fromKeyframe, lc.toKeyframe);
  return pairs;
}

TLiveFrame makeLiveFrame(
    const frontend::TFrameResult& result, const io::TRGBDFrame& frame,
    const graphslam::CSlamContext& context, bool withImage, std::size_t maxCloudPoints,
    std::size_t loopsSeen)
{
  TLiveFrame f;
  f.index = result.frameIndex;
  f.timestamp = result.timestamp;
  f.method = result.method;
  f.pose = result.pose;
  f.referenceKeyframe = result.referenceKeyframe;
  f.relativePose = result.relativePose;
  f.isNewKeyframe = result.isNewKeyframe;
  f.newKeyframeId = result.newKeyframeId;
  const auto& clouds = context.keyframeClouds();
  if (result.isNewKeyframe && result.newKeyframeId < clouds.size())
    f.cloud = decimatedCloud(clouds[result.newKeyframeId], maxCloudPoints);
  f.roi = result.roi;
  f.region = result.work.region;
  f.features = result.features;
  f.trackingFeatures = result.trackingFeatures;
  f.inliers = result.inliers;
  f.extension = result.work.extension;
  if (withImage)
  {
    f.rgb = shareOrCopy(frame.rgb);
    f.depth = shareOrCopy(frame.depth);
    f.featurePixels = context.odometry().lastFeaturePixels();
  }
  const auto& st = context.odometry().stats();
  f.keyframes = context.odometry().keyframes().size();
  f.loopClosures = context.loopClosures().size();
  f.fallbackFrames = st.fullImageFallback + st.depthIcp + st.constantVelocity;
  f.lostFrames = st.lost;
  if (f.loopClosures != loopsSeen)
    f.loops = loopPairs(context);
  return f;
}
}  // namespace roislam::gui
