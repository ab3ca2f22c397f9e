#include "roislam/kfslam/COdometryIncrements.h"

#include <mrpt/core/bits_math.h>
#include <roislam/io/ObservationConversion.h>

#include <Eigen/Dense>
#include <cmath>

namespace roislam::kfslam
{
using mrpt::math::CMatrixDouble66;
using mrpt::poses::CPose3D;
using mrpt::poses::CPose3DPDFGaussian;

COdometryIncrements::COdometryIncrements(
    const TKfSlamOptions& options, const mrpt::poses::CPose3D& sensorPose)
    : m_options(options), m_opticalOnRobot(sensorPose + (-io::tumSensorPose()))
{
  m_options.validate();
}

CPose3D COdometryIncrements::robotPose(const CPose3D& camera) const
{
  return camera + (-m_opticalOnRobot);
}

CPose3D COdometryIncrements::cameraPose(const CPose3D& robot) const
{
  return robot + m_opticalOnRobot;
}

CMatrixDouble66 COdometryIncrements::diagonal(double sigmaM, double sigmaDeg) const
{
  CMatrixDouble66 c;
  c.setZero();
  const double sr = mrpt::DEG2RAD(sigmaDeg);
  for (int k = 0; k < 3; ++k)
  {
    c(k, k) = sigmaM * sigmaM;
    c(k + 3, k + 3) = sr * sr;
  }
  return c;
}

CPose3DPDFGaussian COdometryIncrements::registration(const frontend::TFrameResult& r) const
{
  const CMatrixDouble66 weak = diagonal(m_options.weak_sigma_m, m_options.weak_sigma_deg);
  if (r.method == frontend::ETrackingMethod::ConstantVelocity)
    return CPose3DPDFGaussian(r.relativePose, weak);
  const Eigen::Matrix<double, 6, 6> info = r.relativeInformation.asEigen();
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(info);
  if (!info.allFinite() || ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
      ldlt.vectorD().minCoeff() <= 0)
    return CPose3DPDFGaussian(r.relativePose, weak);
  CMatrixDouble66 cov;
  cov = ldlt.solve(Eigen::Matrix<double, 6, 6>::Identity());
  return CPose3DPDFGaussian(r.relativePose, cov);
}

CMatrixDouble66 COdometryIncrements::motionCovariance(const frontend::TFrameResult& r) const
{
  const CMatrixDouble66 floor = diagonal(m_options.odometry_sigma_m, m_options.odometry_sigma_deg);
  if (m_options.odometry_covariance == "fixed")
    return floor;
  const frontend::TFrameResult& p = *m_previous;
  CPose3DPDFGaussian motion = registration(r);
  const bool fromPrevious = p.isNewKeyframe && r.referenceKeyframe == p.newKeyframeId;
  if (!fromPrevious && p.method != frontend::ETrackingMethod::Initial &&
      r.referenceKeyframe == p.referenceKeyframe)
  {
    // r_prev^-1 (+) r: both registrations' noise.
    CPose3DPDFGaussian inv;
    registration(p).inverse(inv);
    inv += motion;
    motion = inv;
  }
  CMatrixDouble66 cov = motion.cov;
  cov += floor;
  return cov;
}

CPose3DPDFGaussian COdometryIncrements::next(const frontend::TFrameResult& r)
{
  if (!r.pose)
    return CPose3DPDFGaussian(
        CPose3D(), diagonal(m_options.weak_sigma_m, m_options.weak_sigma_deg));
  if (!m_previous)
  {
    m_previous = r;
    CMatrixDouble66 zero;
    zero.setZero();
    return CPose3DPDFGaussian(CPose3D(), zero);
  }
  const CPose3D cameraMotion = *r.pose - *m_previous->pose;
  CPose3DPDFGaussian motion(cameraMotion, motionCovariance(r));
  m_previous = r;
  // Into the robot frame: T (+) D (+) T^-1 (T exact).
  CMatrixDouble66 zero;
  zero.setZero();
  CPose3DPDFGaussian robot(m_opticalOnRobot, zero);
  robot += motion;
  robot += CPose3DPDFGaussian(-m_opticalOnRobot, zero);
  return robot;
}
}  // namespace roislam::kfslam
