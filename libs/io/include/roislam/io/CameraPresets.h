/* Camera intrinsics of the TUM RGB-D benchmark (calibrated Freiburg 1/2/3
 * values, ROS default) and the resolution of a `--camera` argument. Used by
 * the frame sources and tum2rawlog.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/img/TCamera.h>

#include <string>

namespace roislam::io
{
/** A TCamera from one ini section (TCamera's keys). Unlike MRPT 2.5 alone, a
 *  non-zero `dist` without `distortion_model` is read as plumb_bob (MRPT's
 *  older layout). Throws std::runtime_error naming the section. */
mrpt::img::TCamera cameraFromConfig(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section);

/** Intrinsics of a named preset: "fr1", "fr2", "fr3" or "ros" (640x480).
 *  fr1/fr2 carry the benchmark's distortion coefficients; fr3 and ros have none
 *  (fr3 images are already undistorted). Throws std::invalid_argument otherwise. */
mrpt::img::TCamera cameraPreset(const std::string& name);

/** Resolves a --camera value for a dataset folder:
 *  - "auto": "freiburg1|2|3" in the folder name selects fr1/fr2/fr3; a file
 *    "camera.ini" or "camera.yaml" written by rgbd-simul in the folder wins;
 *    otherwise "ros".
 *  - "fr1" | "fr2" | "fr3" | "ros": the preset.
 *  - anything else: a calibration file: MRPT TCamera ini ([CAMERA_PARAMS]
 *    resolution, cx, cy, fx, fy, dist) as written by TCamera::saveToConfigFile.
 *  Throws std::runtime_error naming the file or value when it cannot resolve. */
mrpt::img::TCamera resolveCamera(const std::string& spec, const std::string& datasetDir);
}  // namespace roislam::io
