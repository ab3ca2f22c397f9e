/* The estimator's edge information of a feature registration against the
 * truth: with independent keypoint noise it is honest (chi² about 6 per
 * edge), and a shift common to all keypoints of an image, which no residual
 * shows and which does not average down with the keypoint count, is honest
 * only when the information carries it (TRefineParams::commonPixelSigma).
 */
#include <gtest/gtest.h>
#include <roislam/geometry/Rotation.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "ReprojectionRefinement.h"
#include "RigidMath.h"

namespace detail = roislam::frontend::detail;

namespace
{
/** One registration's chi² against the truth, over `trials` random scenes
 *  whose images are shifted by `commonPx` (1 sigma per axis) each, with the
 *  information built for `modelCommonPx`. Returns the mean chi². */
double meanChi2(double commonPx, double modelCommonPx, int trials, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0, 1);
  std::uniform_real_distribution<double> U(0, 1);
  const roislam::geometry::TPinhole cam{525, 525, 319.5, 239.5};
  const double pixelSigma = 0.5;
  detail::TRefineParams p;
  p.pixelSigma = pixelSigma;
  p.inlierThresholdPx = 100;  // every pair stays in: the test is the information
  p.inlierThreshold3d = 1.0;
  p.huber = 50;
  p.commonPixelSigma = modelCommonPx;
  double sum = 0;
  for (int trial = 0; trial < trials; ++trial)
  {
    // T maps b-coordinates to a-coordinates: 3 cm and 2 degrees.
    detail::TRigid T;
    Eigen::Vector3d axis(N(rng), N(rng), N(rng));
    T.R = roislam::geometry::expSO3(axis.normalized() * 2.0 * M_PI / 180);
    Eigen::Vector3d dir(N(rng), N(rng), N(rng));
    T.t = 0.03 * dir.normalized();
    const detail::TRigid Tinv = T.inverse();
    const Eigen::Vector2d shiftA(commonPx * N(rng), commonPx * N(rng));
    const Eigen::Vector2d shiftB(commonPx * N(rng), commonPx * N(rng));
    detail::TCorrespondences c;
    for (int i = 0; i < 150; ++i)
    {
      const double z = 1 + 3 * U(rng);
      const Eigen::Vector3d a(
          (20 + 600 * U(rng) - cam.cx) / cam.fx * z, (20 + 440 * U(rng) - cam.cy) / cam.fy * z, z);
      const Eigen::Vector3d b = Tinv * a;
      if (b.z() < 0.5)
        continue;
      const auto pix = [&](const Eigen::Vector3d& X, const Eigen::Vector2d& shift)
      {
        return Eigen::Vector2d(
            cam.fx * X.x() / X.z() + cam.cx + shift.x() + pixelSigma * N(rng),
            cam.fy * X.y() / X.z() + cam.cy + shift.y() + pixelSigma * N(rng));
      };
      const Eigen::Vector2d ua = pix(a, shiftA), ub = pix(b, shiftB);
      // Each point is lifted from its measured pixel at its true depth.
      const auto lift = [&](const Eigen::Vector2d& u, double depth)
      {
        return Eigen::Vector3d(
            (u.x() - cam.cx) / cam.fx * depth, (u.y() - cam.cy) / cam.fy * depth, depth);
      };
      c.a.push_back(lift(ua, a.z()));
      c.b.push_back(lift(ub, b.z()));
      c.ua.push_back(ua);
      c.ub.push_back(ub);
    }
    std::vector<std::size_t> all(c.size());
    for (std::size_t i = 0; i < all.size(); ++i)
      all[i] = i;
    const detail::TRefineResult r = detail::refineReprojection(cam, c, T, all, p);
    EXPECT_EQ(r.inliers.size(), c.size());
    const detail::Vector6d d = detail::leftDifference(T, r.T);
    sum += d.dot(r.edgeInformation * d);
  }
  return sum / trials;
}
}  // namespace

TEST(ReprojectionRefinement, EdgeInformationIsHonestForIndependentKeypointNoise)
{
  const double chi2 = meanChi2(0.0, 0.0, 300, 1);
  EXPECT_GT(chi2, 4.5);
  EXPECT_LT(chi2, 7.5);
  // The term widens the information only: on the same data it reads lower.
  EXPECT_LT(meanChi2(0.0, 1.0, 300, 1), chi2);
}

TEST(ReprojectionRefinement, AShiftCommonToAnImageNeedsItsOwnTerm)
{
  // 1 px common to each image against 0.5 px per keypoint: 150 keypoints
  // average their own noise down, not the shift.
  const double without = meanChi2(1.0, 0.0, 300, 2);
  const double with = meanChi2(1.0, 1.0, 300, 2);
  EXPECT_GT(without, 100.0);  // 1200 as written
  EXPECT_GT(with, 4.5);
  EXPECT_LT(with, 7.5);
}
