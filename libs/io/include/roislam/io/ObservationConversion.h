/* Conversions between TRGBDFrame and mrpt::obs::CObservation3DRangeScan, and
 * the sensor-pose convention of roislam rawlogs. Used by CRawlogFrameSource
 * (observation -> frame), tum2rawlog and the simulator (frame -> observation).
 *
 * Sensor-pose convention of roislam rawlogs: obs.sensorPose = tumSensorPose()
 * = -CPose3D(0,0,0,-90deg,0,-90deg), i.e. the "robot" frame IS the TUM optical
 * camera frame (+Z forward, +X right, +Y down). Then
 * obs.unprojectInto(points, {takeIntoAccountSensorPoseOnRobot = true}) gives
 * points in the optical frame, and with robotPoseInTheWorld = the TUM
 * ground-truth pose (pose of the optical centre in the world) world points.
 */
#pragma once

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/io/TRGBDFrame.h>
#include <roislam/io/TSensorDescription.h>

#include <string>

namespace roislam::io
{
/** Pose of the MRPT depth-camera frame (x forward, y left, z up) relative to
 *  the TUM optical frame: the sensorPose every roislam rawlog uses. */
mrpt::poses::CPose3D tumSensorPose();

/** Builds an observation from a raw CV_16UC1 depth image registered to
 *  `camera` (value * rangeUnits = metres, 0 = invalid): sensorLabel "RGBD",
 *  cameraParams = cameraParamsIntensity = camera, cameras coincide,
 *  range_is_depth, sensorPose = tumSensorPose(), timestamp = colour stamp.
 *  The intensity image is left empty (hasIntensityImage = false): set it
 *  embedded or as external file. Throws std::invalid_argument on a wrong type
 *  or a size different from camera.ncols x camera.nrows. */
mrpt::obs::CObservation3DRangeScan::Ptr observationFromRawDepth(
    const cv::Mat& depthU16, float rangeUnits, const mrpt::img::TCamera& camera, double timestamp);

/** As above for a sensor whose depth may not be registered: the raw depth is
 *  on sensor.depth's grid when !sensor.depth_registered, and the observation
 *  then carries cameraParams = sensor.depth and relativePoseIntensityWRTDepth
 *  from sensor.depth_pose_in_colour, so that observationToFrame() (and MRPT's
 *  own tools) re-project it into the colour camera. rangeUnits = 1/depth_scale. */
mrpt::obs::CObservation3DRangeScan::Ptr observationFromRawDepth(
    const cv::Mat& depthU16, const TSensorDescription& sensor, double timestamp);

/** relativePoseIntensityWRTDepth of an observation whose depth optical frame
 *  sits at depthPoseInColour in the colour optical frame (identity: the value
 *  MRPT reads as "cameras coincide"). */
mrpt::poses::CPose3D intensityPoseWrtDepth(const mrpt::poses::CPose3D& depthPoseInColour);

/** The depth optical frame in the colour optical frame of an observation
 *  (the inverse of intensityPoseWrtDepth()). */
mrpt::poses::CPose3D depthPoseInColour(const mrpt::obs::CObservation3DRangeScan& obs);

/** Depth in metres on the depth camera's grid, re-projected into the colour
 *  camera (the depth camera's pinhole model, the colour camera's with its
 *  distortion; z-buffer: the nearest reading wins; pixels no reading lands
 *  on are 0). The one registration of the project: used by
 *  observationToFrame() and the TUM folder reader. */
cv::Mat registerDepthToColour(
    const cv::Mat& depthMetres, const mrpt::img::TCamera& depthCamera,
    const mrpt::img::TCamera& colourCamera, const mrpt::poses::CPose3D& depthPoseInColour);

/** Builds an observation with embedded colour from a frame; metric depth is
 *  quantised to rangeUnits (rounded; depths beyond 65535 * rangeUnits become 0). */
mrpt::obs::CObservation3DRangeScan::Ptr frameToObservation(
    const TRGBDFrame& frame, float rangeUnits = 1.0f / 5000);

/** An observation's depth in metres on the depth camera's own grid (not
 *  registered, not flipped): rangeUnits honoured, ranges turned into depth
 *  when !range_is_depth. What observationToFrame() registers; the
 *  registration estimate (CDepthColourCalibrator) takes it as it is.
 *  Throws std::runtime_error "<context>: ..." on an empty or mis-sized
 *  range image or rangeUnits <= 0. */
cv::Mat depthMetresOnDepthGrid(
    const mrpt::obs::CObservation3DRangeScan& obs, const std::string& context);

/** Converts a loaded observation (call obs.load() first for external depth) to
 *  a frame: BGR colour, depth in metres (rangeUnits honoured, ranges converted
 *  to depth when !range_is_depth, depth re-projected into the colour camera
 *  when the depth camera differs from it), intrinsics = cameraParamsIntensity,
 *  timestamp = depthTimestamp = obs.timestamp (one stamp per observation).
 *  `context` (e.g. "file.rawlog: observation 12") prefixes error messages.
 *  Throws std::runtime_error when an image is missing or sizes disagree with
 *  the intrinsics. */
TRGBDFrame observationToFrame(
    const mrpt::obs::CObservation3DRangeScan& obs, const std::string& context);
}  // namespace roislam::io
