/* What a SLAM result scene shows: the map (a coloured point cloud and/or
 * occupied octree voxels), the estimated trajectory and, when known, the
 * ground truth. Filled by the SLAM app, turned into an mrpt::opengl scene by
 * CSlamSceneBuilder.
 */
#pragma once

#include <mrpt/maps/CColouredPointsMap.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/opengl/CRenderizable.h>

#include <vector>

namespace roislam::viz
{
struct TSceneContent
{
  /** Map points in the world frame (may be empty). */
  mrpt::maps::CColouredPointsMap cloud;
  /** Extra map representation (e.g. COctoMapVoxels from a COctoMap); may be null. */
  mrpt::opengl::CRenderizable::Ptr mapObject;
  /** Estimated camera positions in the world frame, in time order. */
  std::vector<mrpt::math::TPoint3D> trajectory;
  /** Ground-truth camera positions (already aligned to the estimate's
   *  frame); empty when unknown. */
  std::vector<mrpt::math::TPoint3D> groundTruth;
};
}  // namespace roislam::viz
