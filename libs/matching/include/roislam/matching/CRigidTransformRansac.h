/* 3-D rigid transform from putative point correspondences: minimal-sample
 * (3 pairs) RANSAC with the closed-form alignment of geometry::alignRigid
 * (Eigen::umeyama), adaptive number of iterations, and least-squares refits
 * on the inliers. The one robust rigid estimator of the project: used by the
 * SLAM front end (frame-to-keyframe motion, keyframe-to-keyframe
 * verification) and the landmark database's 3-D recall check
 * (landmarks::fitRigid). Our own implementation rather than mrpt::tfest::se3_l2_robust
 * because that one needs ~80 ms for 300 pairs (findings) and we need < 1 ms.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>

#include <cstdint>
#include <optional>
#include <vector>

namespace roislam::matching
{
struct TRigidRansacResult
{
  /** T such that target[i] ~= T (+) source[i] for the inliers. */
  mrpt::poses::CPose3D transform;
  /** Indices (into the input vectors) of the inliers of `transform`. */
  std::vector<std::size_t> inliers;
  /** RMS distance |target - T(+)source| over the inliers, metres. */
  double rmse = 0;
  /** RANSAC hypotheses evaluated. */
  int iterations = 0;
};

class CRigidTransformRansac
{
 public:
  /** ini section (default "RigidRansac"):
   *  - threshold_m      inlier distance, metres > 0            (default 0.02)
   *  - max_iterations   hypotheses at most, int >= 1            (default 200)
   *  - confidence       stop when P(found an all-inlier sample) (default 0.995)
   *                     reaches this, in (0,1)
   *  - min_inliers      fewer inliers -> no result, int >= 3    (default 8)
   *  - seed             random seed (deterministic runs)        (default 1)
   *  - min_sample_spread  a minimal sample whose source points come closer
   *                     to each other than this many threshold_m is
   *                     skipped (its rotation is ill-conditioned), >= 0;
   *                     0 keeps every non-collinear sample, as points in a
   *                     small region need (a ROI landmark's)  (default 2)
   */
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    double threshold_m = 0.02;
    int max_iterations = 200;
    double confidence = 0.995;
    int min_inliers = 8;
    std::uint32_t seed = 1;
    double min_sample_spread = 2;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };

  CRigidTransformRansac();
  /** Throws std::invalid_argument on invalid options. */
  explicit CRigidTransformRansac(const TOptions& options);

  /** Robust T with target[i] ~= T (+) source[i]. Both vectors must have the
   *  same size (else std::invalid_argument). nullopt when fewer than
   *  min_inliers pairs agree. Deterministic for a given seed. */
  std::optional<TRigidRansacResult> estimate(
      const std::vector<mrpt::math::TPoint3D>& target,
      const std::vector<mrpt::math::TPoint3D>& source) const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::matching
