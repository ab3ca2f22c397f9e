/* The sensor's noise facts, as the front end weighs its registrations by
 * them: the depth-noise model, the keypoint shift common to a colour image,
 * each keypoint's own noise and its timing noise (io::TSensorDescription).
 * Camera facts, not ini keys: every app that runs the front end on a sensor
 * (roi-graphslam and roi-graphslam-engine through
 * graphslam::applySensorFacts, roi-landmarks through
 * kfslam::CKfSlamSession) puts them in with this one function.
 */
#pragma once

#include <roislam/frontend/TRgbdOdometryOptions.h>
#include <roislam/io/TSensorDescription.h>

namespace roislam::frontend
{
/** Copies `sensor`'s noise facts into `o` (depth_noise,
 *  common_pixel_sigma_px, keypoint_sigma_px, keypoint_time_sigma_ms); the
 *  readout is left to the caller (an older ini may set it). */
void applySensorNoise(TRgbdOdometryOptions& o, const io::TSensorDescription& sensor);
}  // namespace roislam::frontend
