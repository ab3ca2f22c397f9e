/* Microsoft's RGB-D Dataset 7-Scenes in its own layout: a sequence folder
 * (e.g. chess/seq-01) of frame-NNNNNN.color.png (24-bit colour),
 * frame-NNNNNN.depth.png (16-bit, millimetres, 65535 where there is no
 * reading) and frame-NNNNNN.pose.txt (the 4x4 camera-to-world matrix,
 * homogeneous, row by row). The colour and depth cameras were not calibrated
 * against each other: the depth images are the depth camera's (the dataset
 * gives its principal point (320, 240) and focal length 585 px), and the
 * poses come from KinectFusion run on that depth, so they are the depth
 * camera's. The frames carry no timestamps: frame i is i / frame_rate.
 *
 * CTumFrameSource reads such a folder as it reads a TUM one (rgb.txt absent,
 * frame-000000.color.png present); resolveSensor("auto") picks the
 * "7scenes" preset for it (CameraPresets.h).
 */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <roislam/io/TumTrajectory.h>

#include <string>
#include <vector>

namespace roislam::io
{
/** One frame of a 7-Scenes sequence folder; file names are absolute paths. */
struct TSevenScenesFrame
{
  std::size_t number = 0;  //!< the NNNNNN of its file names
  std::string colourFile;
  std::string depthFile;
  std::string poseFile;  //!< may not exist (test sequences without poses)
};

/** Whether `dir` holds a 7-Scenes sequence: no rgb.txt and a
 *  frame-NNNNNN.color.png (any number: a sequence may be cut). */
bool isSevenScenesFolder(const std::string& dir);

/** The frames of a 7-Scenes folder in frame-number order: every
 *  frame-NNNNNN.color.png with its depth and pose files. Throws
 *  std::runtime_error naming the file when a colour frame has no depth image,
 *  or the folder when it has no frame. */
std::vector<TSevenScenesFrame> listSevenScenesFrames(const std::string& dir);

/** The ground truth of a 7-Scenes sequence as a TUM trajectory of the colour
 *  camera: frame i's pose.txt (the depth camera's pose, T_world_depth) at
 *  time number / frameRate, composed with the colour camera in the depth
 *  camera's frame: T_world_colour = T_world_depth (+) depthPoseInColour^-1
 *  (identity when depth is registered). A matrix with a non-finite entry is
 *  left out (no ground truth for that frame, as the benchmark's tools skip
 *  such lines); a missing pose file too. Throws std::runtime_error
 *  "<file>: ..." when a pose file is not 4 rows of 4 numbers, or its
 *  rotation is not one (det 1, orthonormal within 1e-3). Empty when no frame
 *  has a pose. */
TTrajectory loadSevenScenesGroundTruth(
    const std::vector<TSevenScenesFrame>& frames, double frameRate,
    const mrpt::poses::CPose3D& depthPoseInColour);
}  // namespace roislam::io
