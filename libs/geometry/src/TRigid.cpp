#include "roislam/geometry/TRigid.h"

namespace roislam::geometry
{
TRigid TRigid::fromPose(const mrpt::poses::CPose3D& p)
{
  TRigid T;
  T.R = p.getRotationMatrix().asEigen();
  T.t = Eigen::Vector3d(p.x(), p.y(), p.z());
  return T;
}

mrpt::poses::CPose3D TRigid::toPose() const
{
  return mrpt::poses::CPose3D::FromRotationAndTranslation(R, t);
}
}  // namespace roislam::geometry
