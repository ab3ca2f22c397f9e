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
     *  absolute floor, 10 um / 1e-5 rad). */
    double convergedStepSigma = 0.1;
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

  CDepthIcp(const TParams& params, const mrpt::img::TCamera& camera);

  /** depth: CV_32F metres at full resolution (distorted, as delivered). */
  TMap buildMap(const cv::Mat& depth) const;

  /** Aligns cur to ref starting at guess; nullopt when too few pairs or the
   *  solution jumps implausibly far from the guess. */
  std::optional<TResult> align(const TMap& ref, const TMap& cur, const TRigid& guess) const;

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
  // when too few pairs or a non-finite step), and the normal equations each
  // iteration (and the final check) builds.
  std::optional<TRigid> gaussNewton(
      const TMap& ref, const TMap& cur, const TRigid& guess, int* iterations) const;
  TNormalEquations normalEquations(
      const TMap& ref, const TMap& cur, const TRigid& T, double gate, int stride) const;

  TParams m_params;
  int m_cols = 0, m_rows = 0;
  double m_fx = 1, m_fy = 1, m_cx = 0, m_cy = 0;  // decimated pinhole
  std::vector<int> m_srcIndex;                    // grid cell -> full-res pixel (or -1)
  std::vector<Eigen::Vector3f> m_rays;            // grid cell -> (x/z, y/z, 1)
};
}  // namespace roislam::frontend::detail
