/* Renders rgbd-simul's ICL-like loop (config/rgbd-simul-icl.ini: global
 * shutter, disparity noise), 90 frames, seed 5, with one setting changed by
 * the caller, into a TUM folder. Shared by the integration tests that
 * reproduce a camera fact in a render (common_shift_itest,
 * colour_time_itest); their targets link roislam::sim.
 */
#pragma once

#include <mrpt/config/CConfigFile.h>
#include <roislam/sim/CRgbdSimulator.h>
#include <roislam/testing/TestData.h>

#include <functional>
#include <string>

namespace roislam::testing
{
/** Writes the render to the folder `seq` after `change` has set its fact. */
inline void writeIclLikeRender(
    const std::string& seq, const std::function<void(sim::CRgbdSimulator::TOptions&)>& change)
{
  sim::CRgbdSimulator::TOptions o;
  o.loadFromConfigFile(
      mrpt::config::CConfigFile(sourceDir() + "/config/rgbd-simul-icl.ini"), "RgbdSimulator");
  o.frames = 90;
  o.seed = 5;
  change(o);
  sim::CRgbdSimulator(o).writeSequence(seq);
}
}  // namespace roislam::testing
