/* Depth noise of a structured-light sensor seen as a disparity camera, the
 * structure of the ICL-NUIM benchmark's depth noise (Handa et al., ICRA
 * 2014): the depth is looked up at a randomly jittered image position
 * (bilinear, so depth edges smear into "flying" pixels), turned into a
 * disparity d = bf / z, disturbed by Gaussian noise, quantised to the
 * sensor's sub-pixel steps, and turned back into depth. Unlike the Kinect
 * model (CKinectNoiseModel) its error grows exactly with z^2 and comes in
 * steps, and depth edges are not dropped. Applied by CRgbdSimulator when
 * [RgbdSimulator] noise_model = disparity; the parameters are those of
 * io::TSensorDescription::TDepthNoise. Deterministic per generator state.
 */
#pragma once

#include <mrpt/random/RandomGenerators.h>
#include <roislam/io/TSensorDescription.h>

#include <opencv2/core/mat.hpp>

namespace roislam::sim
{
class CDisparityNoiseModel
{
 public:
  explicit CDisparityNoiseModel(const io::TSensorDescription::TDepthNoise& p) : m_p(p) {}

  /** depth: CV_32FC1 metres, 0 = no reading; modified in place. Pixels whose
   *  jittered lookup touches "no reading" keep the nearest sample. */
  void corruptDepth(cv::Mat& depth, mrpt::random::CRandomGenerator& rng) const;

 private:
  io::TSensorDescription::TDepthNoise m_p;
};
}  // namespace roislam::sim
