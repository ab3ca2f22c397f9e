#include "roislam/io/CDepthColourCalibrator.h"

#include <mrpt/core/bits_math.h>
#include <mrpt/math/CMatrixFixed.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <opencv2/calib3d.hpp>
#include <stdexcept>

#include "DepthColourEdges.h"

namespace roislam::io
{
namespace
{
// Rotation vector, translation, fx, fy, cx, cy, then the colour lens's k1,
// k2, p1, p2, k3 (cv::projectPoints' Jacobian columns, in its order: the
// lens's are its distortion vector's first five), and the silhouettes'
// outward offset.
constexpr int kProjectionParams = 10;
constexpr int kDistortionParams = 5;
constexpr int kSilhouette = kProjectionParams + kDistortionParams;
constexpr int kParams = kSilhouette + 1;
using TVec = cv::Vec<double, kParams>;
using TMat = cv::Matx<double, kParams, kParams>;

double huberCost(double d, double k)
{
  return d <= k ? 0.5 * d * d : k * (d - 0.5 * k);
}
}  // namespace

struct CDepthColourCalibrator::TParams
{
  cv::Vec3d rvec, tvec;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  /** The colour camera's distortion, as OpenCV takes it (the first
   *  kDistortionParams estimated, the rest the start's); none read as
   *  registered already. */
  cv::Mat dist = cv::Mat::zeros(1, 8, CV_64F);
  double silhouette = 0;  //!< px, outwards (from the near surface to the far one)

  /** The values a description holds (no silhouette offset). */
  static TParams of(const TSensorDescription& s)
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
    p.cx = s.colour.cx();
    p.cy = s.colour.cy();
    for (std::size_t i = 0; i < s.colour.dist.size() && i < 8; ++i)
      p.dist.at<double>(0, int(i)) = s.colour.dist[i];
    return p;
  }
  mrpt::poses::CPose3D pose() const
  {
    cv::Matx33d R;
    cv::Rodrigues(rvec, R);
    mrpt::math::CMatrixDouble44 H;
    H.setIdentity();
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
        H(r, c) = R(r, c);
      H(r, 3) = tvec[r];
    }
    return mrpt::poses::CPose3D(H);
  }
  cv::Matx33d K() const { return {fx, 0, cx, 0, fy, cy, 0, 0, 1}; }
  TVec asVec() const
  {
    TVec v;
    const double values[kProjectionParams] = {rvec[0], rvec[1], rvec[2], tvec[0], tvec[1],
                                              tvec[2], fx,      fy,      cx,      cy};
    for (int k = 0; k < kProjectionParams; ++k)
      v[k] = values[k];
    for (int j = 0; j < kDistortionParams; ++j)
      v[kProjectionParams + j] = dist.at<double>(j);
    v[kSilhouette] = silhouette;
    return v;
  }
  /** v's values, the distortion beyond its first kDistortionParams from `like`. */
  static TParams fromVec(const TVec& v, const TParams& like)
  {
    TParams p;
    p.dist = like.dist.clone();
    for (int j = 0; j < kDistortionParams; ++j)
      p.dist.at<double>(j) = v[kProjectionParams + j];
    p.rvec = {v[0], v[1], v[2]};
    p.tvec = {v[3], v[4], v[5]};
    p.fx = v[6];
    p.fy = v[7];
    p.cx = v[8];
    p.cy = v[9];
    p.silhouette = v[kSilhouette];
    return p;
  }
};

struct CDepthColourCalibrator::TEvaluation
{
  double cost = 0;      //!< robust cost, without the prior
  double meanDist = 0;  //!< mean truncated distance, px
  std::size_t points = 0;
  TMat H;
  TVec g;
};

namespace
{
/** The prior's 1-sigma per value, around the start (whose fx, fy scale the
 *  focal lengths' share). */
TVec priorSigmas(const CDepthColourCalibrator::TOptions& o, double fx, double fy)
{
  TVec s;
  for (int k = 0; k < 3; ++k)
  {
    s[k] = mrpt::DEG2RAD(o.prior_rotation_deg);
    s[3 + k] = o.prior_translation_m;
  }
  s[5] = o.prior_translation_z_m;
  s[6] = o.prior_focal_ratio * fx;
  s[7] = o.prior_focal_ratio * fy;
  s[8] = s[9] = o.prior_principal_px;
  s[10] = o.prior_k1;
  s[11] = o.prior_k2;
  s[12] = s[13] = o.prior_tangential;
  s[14] = o.prior_k3;
  s[kSilhouette] = o.prior_silhouette_px;
  return s;
}
}  // namespace

CDepthColourCalibrator::CDepthColourCalibrator(const TSensorDescription& start)
    : CDepthColourCalibrator(start, TOptions())
{
}

std::string CDepthColourCalibrator::whyNotEstimable(const TSensorDescription& s)
{
  if (s.depth_registered)
    return "the depth is registered already";
  for (const auto* c : {&s.colour, &s.depth})
    if (!(c->fx() > 0) || !(c->fy() > 0))
      return "a negative focal length";
  for (const auto* c : {&s.colour, &s.depth})
    if (c->ncols < 8 || c->nrows < 8)
      return "a camera without a size";
  return "";
}

CDepthColourCalibrator::CDepthColourCalibrator(
    const TSensorDescription& start, const TOptions& options)
    : m_start(start), m_options(options)
{
  if (const std::string why = whyNotEstimable(start); !why.empty())
    throw std::invalid_argument("CDepthColourCalibrator: " + why);
  // k1, k2 come before p1, p2 and k3 in the parameters: these counts are the
  // models OpenCV's order allows (radial, then decentring, then k3).
  const int terms = options.distortion_terms;
  if (terms != 0 && terms != 2 && terms != 4 && terms != 5)
    throw std::invalid_argument("CDepthColourCalibrator: distortion_terms must be 0, 2, 4 or 5");
  // Reference readings: a grid over the depth image at 1, 2 and 4 m.
  const auto& dcam = start.depth;
  for (double z : {1.0, 2.0, 4.0})
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 6; ++j)
      {
        const double u = (i + 0.5) * dcam.ncols / 8.0, v = (j + 0.5) * dcam.nrows / 6.0;
        m_reference.emplace_back(
            (u - dcam.cx()) / dcam.fx() * z, (v - dcam.cy()) / dcam.fy() * z, z);
      }
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

  auto silhouettes = detail::findSilhouettes(
      depth, dc, m_options.min_jump_m, m_options.min_jump_ratio, m_options.max_points_per_frame);
  if (silhouettes.points.empty())
    return;
  auto edges = detail::colourEdgeField(colourBgr);
  m_frames.push_back(
      {std::move(silhouettes.points), std::move(silhouettes.outward), std::move(edges.nearest),
       std::move(edges.at), std::move(edges.normal)});
}

CDepthColourCalibrator::TEvaluation CDepthColourCalibrator::evaluate(
    const TParams& p, const std::vector<std::size_t>& frames, double truncate,
    bool withJacobian) const
{
  TEvaluation e;
  const cv::Matx33d K = p.K();
  double sumDist = 0;
  std::vector<cv::Point2d> img;
  cv::Mat jac;
  for (const std::size_t fi : frames)
  {
    const TFrame& f = m_frames[fi];
    if (withJacobian)
      cv::projectPoints(f.points, p.rvec, p.tvec, K, p.dist, img, jac);
    else
      cv::projectPoints(f.points, p.rvec, p.tvec, K, p.dist, img);
    const double maxU = f.nearest.cols - 1, maxV = f.nearest.rows - 1;
    for (std::size_t i = 0; i < img.size(); ++i)
    {
      ++e.points;
      // A depth camera's silhouettes may sit off the true one, outwards (a
      // structured-light camera's correlation window widens the near
      // surface) or inwards; one offset for all, estimated alongside.
      const double u = img[i].x + p.silhouette * f.outward[i].x,
                   v = img[i].y + p.silhouette * f.outward[i].y;
      const int edge = u >= 0 && v >= 0 && u < maxU && v < maxV
                           ? f.nearest.at<int>(int(std::lround(v)), int(std::lround(u)))
                           : -1;
      const cv::Point2d off =
          edge >= 0 ? cv::Point2d(u, v) - f.edgeAt[std::size_t(edge)] : cv::Point2d();
      const double d = edge >= 0 ? std::hypot(off.x, off.y) : truncate;
      if (d >= truncate)
      {
        sumDist += truncate;
        e.cost += huberCost(truncate, m_options.huber_px);
        continue;
      }
      // Point to line: the offset across the edge (along it, the edge
      // continues and says nothing).
      const cv::Point2d n = f.edgeNormal[std::size_t(edge)];
      const double r = n.dot(off), ar = std::abs(r);
      sumDist += d;
      e.cost += huberCost(ar, m_options.huber_px);
      if (!withJacobian)
        continue;
      const double w = ar <= m_options.huber_px ? 1.0 : m_options.huber_px / ar;
      const double* ju = jac.ptr<double>(static_cast<int>(2 * i));
      const double* jv = jac.ptr<double>(static_cast<int>(2 * i + 1));
      TVec J;
      for (int k = 0; k < kSilhouette; ++k)
        J[k] = n.x * ju[k] + n.y * jv[k];
      J[kSilhouette] = n.dot(f.outward[i]);
      for (int a = 0; a < kParams; ++a)
      {
        e.g[a] += w * J[a] * r;
        for (int b = 0; b < kParams; ++b)
          e.H(a, b) += w * J[a] * J[b];
      }
    }
  }
  e.meanDist = e.points ? sumDist / double(e.points) : 0;
  return e;
}

CDepthColourCalibrator::TParams CDepthColourCalibrator::solve(
    TParams p, const std::vector<std::size_t>& frames) const
{
  const TParams start = TParams::of(m_start);
  const TVec theta0 = start.asVec(), sig = priorSigmas(m_options, start.fx, start.fy);
  // Distortion terms beyond distortion_terms held at the start's: their
  // rows of the normal equations replaced by "no change".
  const int terms = m_options.distortion_terms;
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
    for (int k = kProjectionParams + terms; k < kSilhouette; ++k)
    {
      for (int j = 0; j < kParams; ++j)
        e.H(k, j) = e.H(j, k) = 0;
      e.H(k, k) = 1;
      e.g[k] = 0;
    }
    TVec delta;
    if (!cv::solve(e.H, -e.g, delta, cv::DECOMP_CHOLESKY))
      break;
    const double before = e.cost + priorCost(th);
    bool improved = false;
    for (double scale = 1; scale > 1e-3; scale *= 0.5)
    {
      const TVec cand = th + scale * delta;
      const TParams q = TParams::fromVec(cand, start);
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
}

std::vector<cv::Point2d> CDepthColourCalibrator::projectReference(const TParams& p) const
{
  std::vector<cv::Point2d> out;
  cv::projectPoints(m_reference, p.rvec, p.tvec, p.K(), p.dist, out);
  return out;
}

double CDepthColourCalibrator::groupSpreadPx(const TParams& joint) const
{
  // Each interleaved group is estimated alone from the joint estimate,
  // under the same prior; the spread is measured where it matters, in where
  // depth readings land in the colour image. A rotation and a shift of the
  // principal point move the projections nearly alike, so each alone may
  // wander while the registration is well determined. (Under a wider prior
  // the depth offset, which the edges hardly tell from the focal length,
  // wanders by millimetres even where the joint estimate is right; the
  // prior fixes it, and the plausibility test of whyNotUsed() guards it.)
  const int G = std::max(2, m_options.groups);
  std::vector<std::vector<cv::Point2d>> proj;
  for (int g = 0; g < G; ++g)
  {
    std::vector<std::size_t> frames;
    for (std::size_t i = static_cast<std::size_t>(g); i < m_frames.size(); i += std::size_t(G))
      frames.push_back(i);
    if (!frames.empty())
      proj.push_back(projectReference(solve(joint, frames)));
  }
  const double n = double(proj.size());
  double sq = 0;
  for (std::size_t k = 0; k < m_reference.size(); ++k)
  {
    cv::Point2d mean(0, 0);
    for (const auto& pr : proj)
      mean += pr[k] / n;
    for (const auto& pr : proj)
      sq += (pr[k] - mean).dot(pr[k] - mean);
  }
  return std::sqrt(sq / (double(m_reference.size()) * std::max(1.0, n - 1)) / n);
}

std::string CDepthColourCalibrator::whereDistortionFolds(const TParams& p) const
{
  // Along rays from the principal point, the distorted radius must grow
  // until the image's border is reached: a polynomial fitted to where the
  // edges are may turn back beyond them, and an image point would then have
  // two rays (undistortion would pick one at random).
  const auto& cc = m_start.colour;
  const cv::Point2d pp(p.cx, p.cy);
  std::vector<cv::Point3d> ray;
  std::vector<cv::Point2d> px;
  for (int a = 0; a < 72; ++a)
  {
    const double th = a * CV_PI / 36, cx = std::cos(th), cy = std::sin(th);
    ray.clear();
    for (double r = 0.005; r < 3; r += 0.005)
      ray.emplace_back(r * cx / p.fx * p.fy, r * cy, 1.0);
    cv::projectPoints(ray, cv::Vec3d(), cv::Vec3d(), p.K(), p.dist, px);
    double last = 0;
    bool out = false;
    for (std::size_t i = 0; i < px.size() && !out; ++i)
    {
      const cv::Point2d q = px[i];
      const double along = (q - pp).dot(cv::Point2d(cx, cy));
      if (!(along > last))
        return "folds back inside the image";
      last = along;
      out = q.x < 0 || q.y < 0 || q.x > cc.ncols - 1 || q.y > cc.nrows - 1;
    }
    if (!out)
      return "never reaches the image's border";
  }
  return "";
}

std::string CDepthColourCalibrator::whyNotUsed(const TResult& res, const TParams& joint) const
{
  char why[300] = "";
  // Far outside what is known of the camera (the prior) is a failure of the
  // measurement more likely than a camera that different: a real Kinect
  // recording's edges pull the focal length and the depth offset along the
  // direction they cannot tell apart.
  const TParams start = TParams::of(m_start);
  const TVec sig = priorSigmas(m_options, start.fx, start.fy),
             change = joint.asVec() - start.asVec();
  static const char* const kNames[kParams] = {
      "rotation x",
      "rotation y",
      "rotation z",
      "translation x",
      "translation y",
      "translation z",
      "fx",
      "fy",
      "cx",
      "cy",
      "k1",
      "k2",
      "p1",
      "p2",
      "k3",
      "silhouette offset"};
  // A lens that is no lens first (it says most about the estimate).
  if (const std::string fold = whereDistortionFolds(joint); !fold.empty())
    std::snprintf(why, sizeof(why), "the estimated lens %s: implausible", fold.c_str());
  for (int k = 0; k < kParams && !*why; ++k)
    if (std::abs(change[k]) > m_options.max_prior_sigmas * sig[k])
      std::snprintf(
          why, sizeof(why), "%s moved %.1f prior sigmas (> %.1f): implausible", kNames[k],
          std::abs(change[k]) / sig[k], m_options.max_prior_sigmas);
  // A description that says "not registered" of depth that is (a recording
  // whose registration flag was lost, say) gives a start far off, which an
  // estimate may chase into a wrong corner; the data tells it: the depth
  // read as registered fits better than the start, and better than a
  // plausible estimate.
  const bool implausible = *why != 0;
  if (res.distanceRegisteredPx > 0 &&
      res.distanceRegisteredPx < m_options.registered_ratio * res.distanceStartPx &&
      (implausible || res.distanceRegisteredPx < res.distanceEstimatePx))
    std::snprintf(
        why, sizeof(why),
        "the depth fits the colour better as it is, as if registered already (%.2f px against "
        "%.2f at the start): is depth_registered = false right?",
        res.distanceRegisteredPx, res.distanceStartPx);
  if (!*why && res.spreadPx > m_options.max_spread_px)
    std::snprintf(
        why, sizeof(why), "not well determined: spread %.2f px > %.2f", res.spreadPx,
        m_options.max_spread_px);
  // The method's own error: on renders whose cameras are known, the
  // estimate lands depth readings 0.29-0.34 px from where the true cameras
  // do (a render's edges, its rolling shutter), and a SLAM run pays for
  // that much (README: a principal point 1.5 px off costs 1.83 -> 2.47 mm).
  // An estimate that close to the start is not worth taking.
  if (!*why && res.changePx < m_options.min_change_px)
    std::snprintf(
        why, sizeof(why), "within %.2f px of the start (< %.2f): the start kept", res.changePx,
        m_options.min_change_px);
  if (!*why && !(res.distanceEstimatePx < res.distanceStartPx))
    std::snprintf(why, sizeof(why), "the edges fit no better than at the start");
  return why;
}

CDepthColourCalibrator::TResult CDepthColourCalibrator::estimate() const
{
  TResult res;
  res.sensor = m_start;
  res.frames = m_frames.size();
  for (const auto& f : m_frames)
    res.points += f.points.size();
  // The values reported: the start's until there is an estimate.
  const auto report = [&res](const TParams& p)
  {
    res.estimatedPose = p.pose();
    res.estimatedFx = p.fx;
    res.estimatedFy = p.fy;
    res.estimatedCx = p.cx;
    res.estimatedCy = p.cy;
    res.estimatedK1 = p.dist.at<double>(0);
    res.estimatedK2 = p.dist.at<double>(1);
    res.estimatedP1 = p.dist.at<double>(2);
    res.estimatedP2 = p.dist.at<double>(3);
    res.estimatedK3 = p.dist.at<double>(4);
    res.silhouetteOffsetPx = p.silhouette;
  };
  const TParams start = TParams::of(m_start);
  report(start);
  res.estimatedPose = m_start.depth_pose_in_colour;  // exactly, not through a rotation vector
  if (m_frames.size() < m_options.min_frames)
  {
    res.reason = "only " + std::to_string(m_frames.size()) + " frame(s) with depth edges (" +
                 std::to_string(m_options.min_frames) + " needed)";
    return res;
  }

  std::vector<std::size_t> all(m_frames.size());
  std::iota(all.begin(), all.end(), 0);
  const TParams joint = solve(start, all);
  report(joint);

  res.distanceStartPx = evaluate(start, all, m_options.truncate_px, false).meanDist;
  res.distanceEstimatePx = evaluate(joint, all, m_options.truncate_px, false).meanDist;
  // The other reading of the same data: depth already on the colour grid
  // (the depth camera's pixels taken as the colour camera's).
  const auto& cc = m_start.colour;
  const auto& dcam = m_start.depth;
  if (dcam.ncols == cc.ncols && dcam.nrows == cc.nrows)
  {
    TParams registered;
    registered.fx = dcam.fx();
    registered.fy = dcam.fy();
    registered.cx = dcam.cx();
    registered.cy = dcam.cy();
    res.distanceRegisteredPx = evaluate(registered, all, m_options.truncate_px, false).meanDist;
  }
  res.spreadPx = groupSpreadPx(joint);
  {
    const auto a = projectReference(start), b = projectReference(joint);
    double d2 = 0;
    for (std::size_t k = 0; k < m_reference.size(); ++k)
      d2 += (a[k] - b[k]).dot(a[k] - b[k]);
    res.changePx = std::sqrt(d2 / double(m_reference.size()));
  }

  if (const std::string why = whyNotUsed(res, joint); !why.empty())
  {
    res.reason = "not used: " + why;
    return res;
  }
  res.accepted = true;
  res.reason = "well determined";
  res.sensor.depth_pose_in_colour = res.estimatedPose;
  res.sensor.colour.setIntrinsicParamsFromValues(joint.fx, joint.fy, joint.cx, joint.cy);
  for (int j = 0; j < kDistortionParams; ++j)
    res.sensor.colour.dist[std::size_t(j)] = joint.dist.at<double>(j);
  if (std::any_of(
          res.sensor.colour.dist.begin(), res.sensor.colour.dist.end(),
          [](double d) { return d != 0; }))
    res.sensor.colour.distortion = mrpt::img::DistortionModel::plumb_bob;
  res.sensor.estimate_registration = false;
  return res;
}

std::string CDepthColourCalibrator::TResult::summary() const
{
  const auto& p = estimatedPose;
  char text[800];
  std::snprintf(
      text, sizeof(text),
      "%s from %zu frames (%zu depth-edge points): depth pose in colour [%.4f %.4f %.4f m %.2f "
      "%.2f "
      "%.2f deg], colour fx %.1f fy %.1f cx %.1f cy %.1f k1 %.3f k2 %.3f p1 %.4f p2 %.4f k3 %.3f, "
      "silhouettes %+.2f px; "
      "edge distance "
      "%.2f -> %.2f px, spread "
      "%.2f px, %.2f px from the start: %s",
      accepted ? "registration estimated" : "registration estimate not used", frames, points, p.x(),
      p.y(), p.z(), mrpt::RAD2DEG(p.yaw()), mrpt::RAD2DEG(p.pitch()), mrpt::RAD2DEG(p.roll()),
      estimatedFx, estimatedFy, estimatedCx, estimatedCy, estimatedK1, estimatedK2, estimatedP1,
      estimatedP2, estimatedK3, silhouetteOffsetPx, distanceStartPx, distanceEstimatePx, spreadPx,
      changePx, reason.c_str());
  return text;
}
}  // namespace roislam::io
