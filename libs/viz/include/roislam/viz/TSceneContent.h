/* What a SLAM result scene shows: the map (a coloured point cloud and/or
 * occupied octree voxels), the estimated trajectory with its keyframes and,
 * when known, the ground truth, plus the snapshot's legend. Filled by
 * CSlamOutputWriter (in its gravity-up frame, z up), turned into an
 * mrpt::opengl scene by CSlamSceneBuilder and into a PNG by
 * CSnapshotRenderer.
 */
#pragma once

#include <mrpt/maps/CColouredPointsMap.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/opengl/CRenderizable.h>

#include <string>
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
  /** Ground-truth camera positions (already in the same frame as the
   *  estimate); empty when unknown. */
  std::vector<mrpt::math::TPoint3D> groundTruth;
  /** Keyframe positions (marked on the trajectory); may be empty. */
  std::vector<mrpt::math::TPoint3D> keyframes;
  /** Mean direction the cameras looked (any length; zero = unknown): the
   *  snapshot's 3-D view looks the same way, from behind and above. */
  mrpt::math::TVector3D lookDirection{0, 0, 0};
  /** The snapshot's legend, one line each (e.g. "roi_big, ORB",
   *  "ATE RMSE 0.0092 m"); empty = no text lines. */
  std::vector<std::string> legend;
};
}  // namespace roislam::viz
