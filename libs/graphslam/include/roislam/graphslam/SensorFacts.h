/* The camera facts a SLAM run takes from its sensor description
 * (io::TSensorChoice, CFrameSource::sensor(): --camera, the folder's or
 * rawlog's camera.ini, or auto) instead of from the mode config: the colour
 * camera's rolling-shutter readout and the depth-noise model the estimator's
 * edge information is weighted by. The one place roi-graphslam
 * (CRoiGraphSlamApp) and roi-graphslam-engine (CRoiGraphSlamEngineApp) apply
 * them, so both run the same front end on the same sensor.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/io/TSensorChoice.h>

#include <functional>
#include <string>

namespace roislam::graphslam
{
/** Whether `cfg` still sets the front end's rolling_shutter_ms (configs
 *  before the sensor description): [FrontEnd] in roi-graphslam's layout,
 *  [NodeRegistrationDeciderParameters] in MRPT's (SlamIni.h). */
bool iniSetsReadout(const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel);

/** Puts the sensor's camera facts into `fe`: its depth-noise model always,
 *  its signed readout unless `iniReadout` (the ini's value then wins, and a
 *  note line says so when they differ). Prints the choice's summary line
 *  first. Lines go to `progress` (may be empty), headed "<app>: ". */
void applySensorFacts(
    frontend::CRgbdOdometry::TOptions& fe, const io::TSensorChoice& choice, bool iniReadout,
    const std::string& app, const std::string& iniFile,
    const std::function<void(const std::string&)>& progress);

/** summary.json sensor.rolling_shutter_from for a run whose ini did
 *  (`iniReadout`) or did not set the readout. */
std::string readoutOrigin(bool iniReadout);
}  // namespace roislam::graphslam
