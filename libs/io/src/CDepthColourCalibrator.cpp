#include "roislam/io/CDepthColourCalibrator.h"

#include <mrpt/core/bits_math.h>
#include <mrpt/math/CMatrixFixed.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace roislam::io
{
namespace
{
constexpr int kParams = 8;  // rotation vector, translation, fx, fy
using TVec = cv::Vec<double, kParams>;
using TMat = cv::Matx<double, kParams, kParams>;

struct TParams
{
  cv::Vec3d rvec, tvec;
  double fx = 0, fy = 0;

  TVec asVec() const { return {rvec[0], rvec[1], rvec[2], tvec[0], tvec[1], tvec[2], fx, fy}; }
  static TParams fromVec(const TVec& v)
  {
    TParams p;
    p.rvec = {v[0], v[1], v[2]};
    p.tvec = {v[3], v[4], v[5]};
    p.fx = v[6];
    p.fy = v[7];
    return p;
  }
};

TParams paramsOf(const TSensorDescription& s)
{
  const auto H = s.depth_pose_in_colour.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>();
  cv::Matx33d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      R(r, c) = H(r, c);
  TParams p;
  cv::Rodrigues(R, p.rvec);
  p.tvec = {H(0, 3), H(1, 3), H(2, 3)};
  p.fx = s.colour.fx();
  p.fy = s.colour.fy();
  return p;
}

mrpt::poses::CPose3D poseOf(const TParams& p)
{
  cv::Matx33d R;
  cv::Rodrigues(p.rvec, R);
  mrpt::math::CMatrixDouble44 H;
  H.setIdentity();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
      H(r, c) = R(r, c);
    H(r, 3) = p.tvec[r];
  }
  return mrpt::poses::CPose3D(H);
}

float bilinear(const cv::Mat& m, double u, double v)
{
  const int x = static_cast<int>(u), y = static_cast<int>(v);
  const float a = static_cast<float>(u - x), b = static_cast<float>(v - y);
  const float* r0 = m.ptr<float>(y);
  const float* r1 = m.ptr<float>(y + 1);
  return (1 - b) * ((1 - a) * r0[x] + a * r0[x + 1]) + b * ((1 - a) * r1[x] + a * r1[x + 1]);
}

double huberCost(double d, double k)
{
  return d <= k ? 0.5 * d * d : k * (d - 0.5 * k);
}

/** Canny edges with thresholds from the image's own gradient statistics:
 *  the strongest 10 % of gradients start an edge, half that continues it
 *  (a fixed threshold would find no edge in a dim scene, clutter in a
 *  bright one). */
cv::Mat colourEdges(const cv::Mat& bgr)
{
  cv::Mat gray, dx, dy;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  cv::GaussianBlur(gray, gray, cv::Size(3, 3), 0);
  cv::Sobel(gray, dx, CV_16S, 1, 0, 3);
  cv::Sobel(gray, dy, CV_16S, 0, 1, 3);
  std::vector<float> mags;
  mags.reserve(static_cast<std::size_t>(gray.total()));
  for (int r = 0; r < gray.rows; ++r)
  {
    const auto* px = dx.ptr<int16_t>(r);
    const auto* py = dy.ptr<int16_t>(r);
    for (int c = 0; c < gray.cols; ++c)
      mags.push_back(std::hypot(float(px[c]), float(py[c])));
  }
  const auto nth = mags.begin() + static_cast<std::ptrdiff_t>(0.9 * double(mags.size()));
  std::nth_element(mags.begin(), nth, mags.end());
  const double high = std::max(double(*nth), 40.0);
  cv::Mat edges;
  cv::Canny(dx, dy, edges, 0.5 * high, high, true);
  return edges;
}
}  // namespace

CDepthColourCalibrator::CDepthColourCalibrator(const TSensorDescription& start)
    : CDepthColourCalibrator(start, TOptions())
{
}

CDepthColourCalibrator::CDepthColourCalibrator(
    const TSensorDescription& start, const TOptions& options)
    : m_start(start), m_options(options)
{
  if (start.depth_registered)
    throw std::invalid_argument("CDepthColourCalibrator: the depth is registered already");
  for (const auto* c : {&start.colour, &start.depth})
    if (!(c->fx() > 0) || !(c->fy() > 0) || c->ncols < 8 || c->nrows < 8)
      throw std::invalid_argument(
          "CDepthColourCalibrator: the cameras need positive focal lengths and a size");
}

void CDepthColourCalibrator::addFrame(const cv::Mat& colourBgr, const cv::Mat& depth)
{
  const auto& cc = m_start.colour;
  const auto& dc = m_start.depth;
  if (colourBgr.type() != CV_8UC3 || colourBgr.cols != int(cc.ncols) ||
      colourBgr.rows != int(cc.nrows))
    throw std::invalid_argument(
        "CDepthColourCalibrator: colour must be CV_8UC3 of the colour camera's size");
  if (depth.type() != CV_32FC1 || depth.cols != int(dc.ncols) || depth.rows != int(dc.nrows))
    throw std::invalid_argument(
        "CDepthColourCalibrator: depth must be CV_32FC1 of the depth camera's size");

  // Silhouettes: the nearer side of a jump between two valid readings. Depth
  // cameras leave a band of no readings along a jump (the projector's
  // shadow, pixels that mix both surfaces), so the farther reading is looked
  // for across up to kMaxGap missing pixels; the pixel itself must be on the
  // near surface (its neighbour on the other side reads about the same).
  constexpr int kMaxGap = 8;
  std::vector<cv::Point3d> points;
  const double ifx = 1.0 / dc.fx(), ify = 1.0 / dc.fy();
  const auto at = [&](int r, int c)
  { return r >= 0 && c >= 0 && r < depth.rows && c < depth.cols ? depth.at<float>(r, c) : 0.0f; };
  for (int r = 1; r + 1 < depth.rows; ++r)
  {
    const float* row = depth.ptr<float>(r);
    for (int c = 1; c + 1 < depth.cols; ++c)
    {
      const float z = row[c];
      if (!(z > 0))
        continue;
      const double jump = std::max(m_options.min_jump_m, m_options.min_jump_ratio * z);
      for (const auto& [dr, dcol] : {std::pair(0, 1), {0, -1}, {1, 0}, {-1, 0}})
      {
        const float back = depth.at<float>(r - dr, c - dcol);
        if (!(back > 0) || std::abs(back - z) > 0.5 * jump)
          continue;
        float far = 0;
        int k = 0;
        while (!(far > 0) && k <= kMaxGap)
          far = at(r + ++k * dr, c + k * dcol);
        if (!(far > 0 && far - z > jump))
          continue;
        const double u = c + 0.5 * k * dcol, v = r + 0.5 * k * dr;
        points.emplace_back((u - dc.cx()) * ifx * z, (v - dc.cy()) * ify * z, z);
      }
    }
  }
  if (points.empty())
    return;
  TFrame f;
  const std::size_t keep = std::max<std::size_t>(m_options.max_points_per_frame, 1);
  const double step = std::max(1.0, double(points.size()) / double(keep));
  for (double i = 0; i < double(points.size()); i += step)
    f.points.push_back(points[static_cast<std::size_t>(i)]);

  cv::Mat notEdge;
  cv::bitwise_not(colourEdges(colourBgr), notEdge);
  cv::distanceTransform(notEdge, f.distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  cv::Sobel(f.distance, f.gradX, CV_32F, 1, 0, 1, 0.5);
  cv::Sobel(f.distance, f.gradY, CV_32F, 0, 1, 1, 0.5);
  m_frames.push_back(std::move(f));
}

namespace
{
struct TEvaluation
{
  double cost = 0;      //!< robust cost, without the prior
  double meanDist = 0;  //!< mean truncated distance, px
  std::size_t points = 0;
  TMat H;
  TVec g;
};
}  // namespace

CDepthColourCalibrator::TResult CDepthColourCalibrator::estimate() const
{
  TResult res;
  res.sensor = m_start;
  res.frames = m_frames.size();
  for (const auto& f : m_frames)
    res.points += f.points.size();
  const TParams start = paramsOf(m_start);
  res.estimatedPose = m_start.depth_pose_in_colour;
  res.estimatedFx = start.fx;
  res.estimatedFy = start.fy;

  const auto& cc = m_start.colour;
  cv::Mat dist(1, static_cast<int>(cc.dist.size()), CV_64F);
  for (std::size_t i = 0; i < cc.dist.size(); ++i)
    dist.at<double>(0, static_cast<int>(i)) = cc.dist[i];

  auto evaluate = [&](const TParams& p, const std::vector<std::size_t>& frames, double truncate,
                      bool withJacobian)
  {
    TEvaluation e;
    const cv::Matx33d K(p.fx, 0, cc.cx(), 0, p.fy, cc.cy(), 0, 0, 1);
    double sumDist = 0;
    std::vector<cv::Point2d> img;
    cv::Mat jac;
    for (const std::size_t fi : frames)
    {
      const TFrame& f = m_frames[fi];
      if (withJacobian)
        cv::projectPoints(f.points, p.rvec, p.tvec, K, dist, img, jac);
      else
        cv::projectPoints(f.points, p.rvec, p.tvec, K, dist, img);
      const double maxU = f.distance.cols - 2, maxV = f.distance.rows - 2;
      for (std::size_t i = 0; i < img.size(); ++i)
      {
        ++e.points;
        const double u = img[i].x, v = img[i].y;
        if (!(u >= 0 && v >= 0 && u < maxU && v < maxV))
        {
          sumDist += truncate;
          e.cost += huberCost(truncate, m_options.huber_px);
          continue;
        }
        const double d = bilinear(f.distance, u, v);
        const double dt = std::min(d, truncate);
        sumDist += dt;
        e.cost += huberCost(dt, m_options.huber_px);
        if (!withJacobian || d >= truncate)
          continue;
        const double w = d <= m_options.huber_px ? 1.0 : m_options.huber_px / d;
        const double gx = bilinear(f.gradX, u, v), gy = bilinear(f.gradY, u, v);
        const double* ju = jac.ptr<double>(static_cast<int>(2 * i));
        const double* jv = jac.ptr<double>(static_cast<int>(2 * i + 1));
        TVec J;
        for (int k = 0; k < kParams; ++k)
          J[k] = gx * ju[k] + gy * jv[k];
        for (int a = 0; a < kParams; ++a)
        {
          e.g[a] += w * J[a] * d;
          for (int b = 0; b < kParams; ++b)
            e.H(a, b) += w * J[a] * J[b];
        }
      }
    }
    e.meanDist = e.points ? sumDist / double(e.points) : 0;
    return e;
  };

  const double rot = mrpt::DEG2RAD(m_options.prior_rotation_deg);
  const double trans = m_options.prior_translation_m;
  auto priorSigmas = [&]()
  {
    TVec s;
    for (int k = 0; k < 3; ++k)
    {
      s[k] = rot;
      s[3 + k] = trans;
    }
    s[5] = m_options.prior_translation_z_m;
    s[6] = m_options.prior_focal_ratio * start.fx;
    s[7] = m_options.prior_focal_ratio * start.fy;
    return s;
  };
  const TVec theta0 = start.asVec();

  auto solve = [&](TParams p, const std::vector<std::size_t>& frames)
  {
    const TVec sig = priorSigmas();
    auto priorCost = [&](const TVec& th)
    {
      double c = 0;
      for (int k = 0; k < kParams; ++k)
        c += 0.5 * std::pow((th[k] - theta0[k]) / sig[k], 2);
      return c;
    };
    for (int it = 0; it < m_options.iterations; ++it)
    {
      // Wide truncation first: the start may be several pixels off.
      const double truncate =
          it < m_options.iterations / 3 ? 2 * m_options.truncate_px : m_options.truncate_px;
      TEvaluation e = evaluate(p, frames, truncate, true);
      const TVec th = p.asVec();
      for (int k = 0; k < kParams; ++k)
      {
        e.H(k, k) += 1.0 / (sig[k] * sig[k]);
        e.g[k] += (th[k] - theta0[k]) / (sig[k] * sig[k]);
      }
      TVec delta;
      if (!cv::solve(e.H, -e.g, delta, cv::DECOMP_CHOLESKY))
        break;
      const double before = e.cost + priorCost(th);
      bool improved = false;
      for (double scale = 1; scale > 1e-3; scale *= 0.5)
      {
        const TVec cand = th + scale * delta;
        const TParams q = TParams::fromVec(cand);
        if (evaluate(q, frames, truncate, false).cost + priorCost(cand) < before)
        {
          p = q;
          improved = true;
          delta *= scale;
          break;
        }
      }
      if (!improved)
        break;
      const bool small = std::abs(delta[0]) + std::abs(delta[1]) + std::abs(delta[2]) < 1e-6 &&
                         std::abs(delta[3]) + std::abs(delta[4]) + std::abs(delta[5]) < 1e-6 &&
                         std::abs(delta[6]) + std::abs(delta[7]) < 1e-3;
      if (small)
        break;
    }
    return p;
  };

  if (m_frames.size() < m_options.min_frames)
  {
    res.reason = "only " + std::to_string(m_frames.size()) + " frame(s) with depth edges (" +
                 std::to_string(m_options.min_frames) + " needed)";
    return res;
  }
  std::vector<std::size_t> all(m_frames.size());
  std::iota(all.begin(), all.end(), 0);
  const TParams joint = solve(start, all);
  res.distanceStartPx = evaluate(start, all, m_options.truncate_px, false).meanDist;
  res.distanceEstimatePx = evaluate(joint, all, m_options.truncate_px, false).meanDist;
  res.estimatedPose = poseOf(joint);
  res.estimatedFx = joint.fx;
  res.estimatedFy = joint.fy;

  // The spread of interleaved groups' estimates, each from the joint one
  // under the same prior: how much the edges of different frames disagree.
  // (Under a wider prior the depth offset, which the edges hardly tell from
  // the focal length, wanders by millimetres even where the joint estimate
  // is right; the prior is what fixes it, and the plausibility test below
  // what guards it.)
  const int G = std::max(2, m_options.groups);
  std::vector<TVec> groupEst;
  for (int g = 0; g < G; ++g)
  {
    std::vector<std::size_t> frames;
    for (std::size_t i = static_cast<std::size_t>(g); i < m_frames.size(); i += std::size_t(G))
      frames.push_back(i);
    if (!frames.empty())
      groupEst.push_back(solve(joint, frames).asVec());
  }
  const double n = double(groupEst.size());
  for (int k = 0; k < kParams; ++k)
  {
    double mean = 0, var = 0;
    for (const auto& v : groupEst)
      mean += v[k] / n;
    for (const auto& v : groupEst)
      var += (v[k] - mean) * (v[k] - mean) / std::max(1.0, n - 1);
    res.sigma[static_cast<std::size_t>(k)] = std::sqrt(var / n);
  }
  // Report rotations in degrees and focal lengths relative.
  for (int k = 0; k < 3; ++k)
  {
    std::swap(res.sigma[std::size_t(k)], res.sigma[std::size_t(k + 3)]);
    res.sigma[std::size_t(k + 3)] = mrpt::RAD2DEG(res.sigma[std::size_t(k + 3)]);
  }
  res.sigma[6] /= joint.fx;
  res.sigma[7] /= joint.fy;

  char why[200] = "";
  // Far outside what is known of the camera (the prior) is a failure of the
  // measurement more likely than a camera that different: a real Kinect
  // recording's edges pull the focal length and the depth offset along the
  // direction they cannot tell apart.
  const TVec sig = priorSigmas(), change = joint.asVec() - theta0;
  static const char* const kNames[kParams] = {
      "rotation x",    "rotation y",    "rotation z", "translation x",
      "translation y", "translation z", "fx",         "fy"};
  for (int k = 0; k < kParams && !*why; ++k)
    if (std::abs(change[k]) > m_options.max_prior_sigmas * sig[k])
      std::snprintf(
          why, sizeof(why), "%s moved %.1f prior sigmas (> %.1f): implausible", kNames[k],
          std::abs(change[k]) / sig[k], m_options.max_prior_sigmas);
  for (int k = 0; k < 3 && !*why; ++k)
    if (res.sigma[std::size_t(k)] > m_options.max_translation_sigma_m)
      std::snprintf(
          why, sizeof(why), "not well determined: translation %c spread %.1f mm > %.1f", "xyz"[k],
          1e3 * res.sigma[std::size_t(k)], 1e3 * m_options.max_translation_sigma_m);
  for (int k = 0; k < 3 && !*why; ++k)
    if (res.sigma[std::size_t(k + 3)] > m_options.max_rotation_sigma_deg)
      std::snprintf(
          why, sizeof(why), "not well determined: rotation %c spread %.3f deg > %.3f", "xyz"[k],
          res.sigma[std::size_t(k + 3)], m_options.max_rotation_sigma_deg);
  for (int k = 0; k < 2 && !*why; ++k)
    if (res.sigma[std::size_t(k + 6)] > m_options.max_focal_sigma_ratio)
      std::snprintf(
          why, sizeof(why), "not well determined: f%c spread %.2f %% > %.2f", "xy"[k],
          100 * res.sigma[std::size_t(k + 6)], 100 * m_options.max_focal_sigma_ratio);
  if (!*why && !(res.distanceEstimatePx < res.distanceStartPx))
    std::snprintf(why, sizeof(why), "the edges fit no better than at the start");
  if (*why)
  {
    res.reason = std::string("not used: ") + why;
    return res;
  }
  res.accepted = true;
  res.reason = "well determined";
  res.sensor.depth_pose_in_colour = res.estimatedPose;
  res.sensor.colour.setIntrinsicParamsFromValues(joint.fx, joint.fy, cc.cx(), cc.cy());
  res.sensor.estimate_registration = false;
  return res;
}

std::string CDepthColourCalibrator::TResult::summary() const
{
  const auto& p = estimatedPose;
  char text[400];
  std::snprintf(
      text, sizeof(text),
      "%s from %zu frames (%zu depth-edge points): depth pose in colour [%.4f %.4f %.4f m %.2f "
      "%.2f "
      "%.2f deg], colour fx %.1f fy %.1f; edge distance %.2f -> %.2f px; spread %.1f %.1f %.1f mm "
      "%.3f %.3f %.3f deg %.2f %.2f %%: %s",
      accepted ? "registration estimated" : "registration estimate not used", frames, points, p.x(),
      p.y(), p.z(), mrpt::RAD2DEG(p.yaw()), mrpt::RAD2DEG(p.pitch()), mrpt::RAD2DEG(p.roll()),
      estimatedFx, estimatedFy, distanceStartPx, distanceEstimatePx, 1e3 * sigma[0], 1e3 * sigma[1],
      1e3 * sigma[2], sigma[3], sigma[4], sigma[5], 100 * sigma[6], 100 * sigma[7], reason.c_str());
  return text;
}
}  // namespace roislam::io
