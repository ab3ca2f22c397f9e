#include "roislam/geometry/RigidAlignment.h"

namespace roislam::geometry
{
std::pair<Eigen::Matrix3Xd, Eigen::Matrix3Xd> gatherPairs(
    const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
    const std::vector<std::size_t>& indices)
{
  if (a.size() != b.size())
    throw std::invalid_argument("gatherPairs: the point sets differ in size");
  const std::size_t n = indices.empty() ? a.size() : indices.size();
  std::pair<Eigen::Matrix3Xd, Eigen::Matrix3Xd> out;
  out.first.resize(3, static_cast<Eigen::Index>(n));
  out.second.resize(3, static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::size_t i = indices.empty() ? k : indices[k];
    if (i >= a.size())
      throw std::out_of_range("gatherPairs: index out of range");
    out.first.col(static_cast<Eigen::Index>(k)) = a[i];
    out.second.col(static_cast<Eigen::Index>(k)) = b[i];
  }
  return out;
}
}  // namespace roislam::geometry
