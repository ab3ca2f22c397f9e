/* Kinect-v1-like corruption of a perfect depth/colour pair, applied by
 * CRgbdSimulator to every rendered frame unless noise is off:
 *  - axial depth noise, Gaussian with sigma(z) = a + b (z - z0)^2 metres
 *    (Nguyen, Izadi, Lovell 2012: 0.0012 + 0.0019 (z - 0.4)^2);
 *  - no reading (0) at depth discontinuities: any pixel whose 3x3
 *    neighbourhood holds a depth differing by more than edgeJumpRatio * z, or
 *    an invalid pixel;
 *  - colour sensor noise, Gaussian with rgbNoiseStd grey levels per channel.
 * The range limits (no reading outside [minDepth, maxDepth]) hold for noise-free
 * frames too and are applied by the simulator separately (applyRange).
 * Deterministic: the per-pixel normal draws come from OpenCV's cv::RNG (fast)
 * seeded with draws of the MRPT generator passed in, so the result depends
 * only on that generator's state.
 */
#pragma once

#include <mrpt/random/RandomGenerators.h>

#include <opencv2/core/mat.hpp>

namespace roislam::sim
{
class CKinectNoiseModel
{
 public:
  struct TParams
  {
    double sigmaA = 0.0012;       //!< metres
    double sigmaB = 0.0019;       //!< metres / metre^2
    double sigmaZ0 = 0.4;         //!< metres
    double edgeJumpRatio = 0.03;  //!< relative depth jump that drops a pixel
    double rgbNoiseStd = 2.0;     //!< grey levels
  };

  explicit CKinectNoiseModel(const TParams& p) : m_p(p) {}

  /** sigma(z) in metres. */
  double depthSigma(double z) const;

  /** depth: CV_32FC1 metres, 0 = invalid; modified in place. */
  void corruptDepth(cv::Mat& depth, mrpt::random::CRandomGenerator& rng) const;
  /** rgb: CV_8UC3; modified in place. */
  void corruptColour(cv::Mat& rgb, mrpt::random::CRandomGenerator& rng) const;

  /** Sets depth outside [minDepth, maxDepth] to 0 (sensor range). */
  static void applyRange(cv::Mat& depth, double minDepth, double maxDepth);

 private:
  TParams m_p;
};
}  // namespace roislam::sim
