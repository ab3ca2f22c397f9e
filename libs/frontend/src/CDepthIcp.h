/* Private: depth-only registration for frames without usable features
 * (featureless walls). Projective point-to-plane ICP (Gauss-Newton, Huber) on a
 * decimated, undistorted depth image: correspondences by projecting the
 * current points into the reference keyframe's vertex/normal map, so no
 * nearest-neighbour search is needed and one alignment takes a few ms.
 * Directions the geometry leaves unconstrained (e.g. sliding along a plane)
 * stay at the initial guess (the constant-velocity prediction) thanks to a
 * small damping term.
 */
#pragma once

#include <mrpt/img/TCamera.h>

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "RigidMath.h"

namespace roislam::frontend::detail
{
class CDepthIcp
{
 public:
  struct TParams
  {
    int decimation = 4;
    int maxIterations = 15;
    /** Stop once a Gauss-Newton step is below this fraction of the pose's
     *  standard deviation under the information ICP claims (0: only the
     *  absolute floor, 10 um / 1e-5 rad). 0.2 under kIndependentPairShare
     *  stops at the step 0.1 stopped at under the earlier 1/100. */
    double convergedStepSigma = 0.2;
    double maxDistance = 0.10;
    int minPairs = 500;
    double minDepth = 0.3;
    double maxDepth = 4.0;
  };

  /** Vertex and normal map on the decimated undistorted grid (NaN = invalid). */
  struct TMap
  {
    int cols = 0, rows = 0;
    std::vector<Eigen::Vector3f> points;
    std::vector<Eigen::Vector3f> normals;
  };

  struct TResult
  {
    TRigid T;                                 //!< maps current-frame points to the reference frame
    Matrix6d information = Matrix6d::Zero();  //!< of the left-perturbation delta
    /** For the pose graph: the point-to-plane Hessian itself (no floor),
     *  nearly zero along directions the surfaces leave free. */
    Matrix6d edgeInformation = Matrix6d::Zero();
    std::size_t pairs = 0;
    double rmse = 0;
    int iterations = 0;  //!< Gauss-Newton iterations run
  };

  /** The share of ICP's pairs counted as independent measurements in the
   *  information it claims (TResult::information, which the front end fuses
   *  with the features' and the convergence test uses, and
   *  TResult::edgeInformation). Dense pairs share their errors (association
   *  on a grid, normals from neighbours, smooth or quantised depth), so
   *  fewer than all count. Measured against ground truth on rgbd-simul's
   *  ICL-like, noise-free, unregistered and 720p loops: with 1/100 (before
   *  stop 37) ICP's pose error read chi-square 0.1-0.35 (median; 5.35 is
   *  honest), i.e. ICP was trusted 15-58x less than it deserved. Over 45
   *  runs (3 modes x ORB/SURF/SIFT x fr1/rpy, fr1/xyz and three loops) 1/25
   *  was the most accurate of 1/100, 1/25, 1/10 and 1, and the fr1 runs
   *  moved by at most 2 %: on the fr1 Kinect the measured fusion scale
   *  (IcpConsistency.h) inflates ICP's covariance by whatever its
   *  disagreement with the features asks for. Still conservative: the ROI
   *  modes' registrations that ICP is fused with are underconfident too
   *  (README "ICP's information against ground truth"). */
  static constexpr double kIndependentPairShare = 0.04;
  /** The share for an ICP edge that stands alone in the graph (features
   *  failed): no feature registration checks it, so it keeps the earlier,
   *  more conservative model. With kIndependentPairShare there too, SURF
   *  and small ROI ORB on fr1/rpy lost 10-27 % (the Kinect's ICP is
   *  overconfident, and nothing measured by how much). */
  static constexpr double kUnverifiedPairShare = 0.01;
  /** How much wider ICP alone's covariance is than its verified one (4):
   *  the fusion scale assumed before IcpConsistency has measured one. */
  static constexpr double kUnverifiedCovarianceScale = kIndependentPairShare / kUnverifiedPairShare;

  CDepthIcp(const TParams& params, const mrpt::img::TCamera& camera);

  /** depth: CV_32F metres at full resolution (distorted, as delivered). */
  TMap buildMap(const cv::Mat& depth) const;

  /** Aligns cur to ref starting at guess; nullopt when too few pairs or the
   *  solution jumps implausibly far from the guess. pairStride > 1 pairs
   *  only every pairStride-th cell of every pairStride-th row of cur (1 /
   *  pairStride^2 of the work; the information claimed falls alike). */
  std::optional<TResult> align(
      const TMap& ref, const TMap& cur, const TRigid& guess, int pairStride = 1) const;

  const TParams& params() const { return m_params; }

 private:
  /** Point-to-plane normal equations of cur against ref at pose T (Huber
   *  weights), from the pairs closer than gate (metres), taking every
   *  stride-th cell of every stride-th row of cur. */
  struct TNormalEquations
  {
    Matrix6d H;
    Vector6d g;
    std::size_t pairs = 0;
    double sumSq = 0;  //!< sum of the squared residuals
  };
  // align()'s steps: the Gauss-Newton iterations from the guess (nullopt
  // when too few pairs or a non-finite step; *converged: the last
  // tight-gate equations when the steps converged, to stand for T's), and
  // the normal equations each iteration (and the final check) builds.
  std::optional<TRigid> gaussNewton(
      const TMap& ref, const TMap& cur, const TRigid& guess, int pairStride, int* iterations,
      std::optional<TNormalEquations>* converged) const;
  TNormalEquations normalEquations(
      const TMap& ref, const TMap& cur, const TRigid& T, double gate, int stride) const;

  TParams m_params;
  int m_cols = 0, m_rows = 0;
  double m_fx = 1, m_fy = 1, m_cx = 0, m_cy = 0;  // decimated pinhole
  std::vector<int> m_srcIndex;                    // grid cell -> full-res pixel (or -1)
  std::vector<Eigen::Vector3f> m_rays;            // grid cell -> (x/z, y/z, 1)
};
}  // namespace roislam::frontend::detail
