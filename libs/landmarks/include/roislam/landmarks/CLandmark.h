/* A landmark of the ROI database: a confirmed ROI as first stored (image
 * patch, keypoints, descriptors, 3-D position from the depth of its features)
 * plus every later sighting. Serializable with MRPT's versioned
 * serialization so a database file can be saved, reloaded and inspected.
 * Created by CLandmarkDatabase; read by the scorer, the observation processor
 * and the SLAM back end.
 */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt/serialization/CSerializable.h>
#include <roislam/features/TFeatureSet.h>
#include <roislam/landmarks/TLandmarkSighting.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace roislam::landmarks
{
class CLandmark : public mrpt::serialization::CSerializable
{
  DEFINE_SERIALIZABLE(CLandmark, roislam::landmarks)

 public:
  /** Database-assigned identifier (0, 1, ...), the landmark ID of the
   *  bearing-range observations. */
  int32_t id = -1;
  /** The ROI's features at first sight; keypoints in the pixel coordinates of
   *  that whole frame (not of the patch). */
  features::TFeatureSet features;
  /** Optical-frame 3-D point of each feature at first sight (NaN where the
   *  depth had no reading), metres; parallel to features.keypoints. Lets a
   *  recall measure where the landmark is by 3-D alignment. */
  std::vector<mrpt::math::TPoint3D> featurePoints;
  /** The ROI box at first sight, pixels of that frame. */
  cv::Rect box;
  /** Size of the frame of first sight. */
  cv::Size imageSize;
  /** Colour crop of the ROI at first sight (CV_8UC3 BGR or CV_8UC1); may be
   *  empty. Stored losslessly (PNG bytes). */
  cv::Mat patch;
  /** Position in the optical camera frame (x right, y down, z forward) of the
   *  first sight, metres: component-wise median of the features' 3-D points. */
  mrpt::math::TPoint3D positionCamera{0, 0, 0};
  bool hasPositionCamera = false;
  /** Position in the world frame, when the camera pose of the first sight was
   *  known (SLAM estimate or given pose). */
  mrpt::math::TPoint3D positionWorld{0, 0, 0};
  bool hasPositionWorld = false;
  /** Every sighting, the first one included, in frame order. */
  std::vector<TLandmarkSighting> sightings;
};
}  // namespace roislam::landmarks
