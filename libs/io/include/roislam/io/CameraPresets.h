/* Camera intrinsics of the TUM RGB-D benchmark (calibrated Freiburg 1/2/3
 * values, ROS default) and the resolution of a `--camera` argument. Used by
 * the frame sources and tum2rawlog.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/img/TCamera.h>
#include <roislam/io/TSensorChoice.h>
#include <roislam/io/TSensorDescription.h>

#include <optional>
#include <string>

namespace roislam::io
{
/** A TCamera from one ini section (TCamera's keys). Unlike MRPT 2.5 alone, a
 *  non-zero `dist` without `distortion_model` is read as plumb_bob (MRPT's
 *  older layout). Throws std::runtime_error naming the section. */
mrpt::img::TCamera cameraFromConfig(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section);

/** Intrinsics of a named preset: "fr1", "fr2", "fr3", "icl", "7scenes" or "ros" (640x480).
 *  fr1/fr2 carry the benchmark's distortion coefficients; fr3, icl and ros have
 *  none (fr3 images are already undistorted). icl is ICL-NUIM's published
 *  camera, fy < 0 (CameraAxes.h). Throws std::invalid_argument otherwise. */
mrpt::img::TCamera cameraPreset(const std::string& name);

/** The description of a preset "fr1", "fr2", "fr3", "icl", "7scenes" or
 *  "ros": cameraPreset()'s intrinsics, depth registered, scale 5000, 30 Hz,
 *  the Kinect depth noise (icl: ICL-NUIM's simulated disparity noise), and a
 *  25 ms top-to-bottom readout for the Kinects fr1/fr2/fr3/7scenes (measured
 *  on fr1), none for icl and ros. 7scenes: depth unregistered (the
 *  dataset's depth camera, 585 px; a Kinect v1's factory extrinsics as the
 *  start of an estimate: estimate_registration), in millimetres. Throws
 *  std::invalid_argument for another name. */
TSensorDescription sensorPreset(const std::string& name);

/** A description file: an ini with [SensorDescription] (TSensorDescription.h),
 *  a plain TCamera ini ([CAMERA_PARAMS] only) or an OpenCV/ROS yaml, the
 *  latter two with the description's defaults (no rolling shutter) and the
 *  file stem as name. Throws std::runtime_error naming the file and key. */
TSensorDescription loadSensorFile(const std::string& file);

/** Resolves a --camera value for a dataset folder (the rules below), with
 *  the reason of the choice. */
TSensorChoice resolveSensor(const std::string& spec, const std::string& datasetDir);

/** Resolves a --camera value for a recording file (a .rawlog or .oni):
 *  "auto" takes <dir>/<stem>.camera.ini when it exists (tum2rawlog writes
 *  one), else nullopt: the source then describes itself (a rawlog by its
 *  observations' intrinsics, OpenNI2 by its device) and says so. Any other
 *  value as resolveSensor() for the file's folder. */
std::optional<TSensorChoice> resolveSensorForFile(const std::string& spec, const std::string& file);

/** The description file that travels with a recording: <dir>/<stem>.camera.ini. */
std::string sensorFileBeside(const std::string& recording);

/** resolveSensor(spec, datasetDir).sensor.colour. Resolves a --camera value for a dataset folder:
 *  - "auto": a file "camera.ini" (a sensor description or a TCamera ini) or
 *    "camera.yaml" in the folder wins; else "freiburg1|2|3" in the folder
 *    name selects fr1/fr2/fr3; else an ICL-NUIM name (a word starting with
 *    "icl", or living_room, office_room, frei_png, lr_kt, of_kt) selects icl;
 *    a folder in 7-Scenes' own layout (SevenScenes.h) 7scenes; otherwise "ros".
 *  - "fr1" | "fr2" | "fr3" | "icl" | "7scenes" | "ros": the preset.
 *  - anything else: a file, as loadSensorFile().
 *  Throws std::runtime_error naming the file or value when it cannot resolve. */
mrpt::img::TCamera resolveCamera(const std::string& spec, const std::string& datasetDir);
}  // namespace roislam::io
