/* A SLAM pipeline run on a sequence with its sensor description applied as
 * the apps apply it (the colour readout and the depth-noise model),
 * evaluated against the sequence's ground truth: the trajectory's ATE and the
 * graph edges' chi-square. Shared by the integration tests that compare one
 * sequence read through two descriptions (camera_axes_itest,
 * seven_scenes_itest, colour_time_itest: ORB, 600 features) or with two
 * settings (colour_check_itest, common_shift_itest).
 */
#pragma once

#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/evaluation/EdgeChi2.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>

#include <optional>
#include <string>
#include <utility>

namespace roislam::testing
{
struct TPipelineRun
{
  io::TTrajectory trajectory;
  evaluation::TAteResult ate;
  /** The graph edges' chi-square against the ground truth (keyframe stamps);
   *  nullopt when no edge could be read against it. */
  std::optional<evaluation::TEdgeChi2> edgeChi2;
  /** TSensorChoice::source of the description it ran with ("preset fr1", "file ..."). */
  std::string sensorSource;
  /** The front end's counts over the run. */
  frontend::CRgbdOdometry::TStats frontEndStats;
};

/** Runs `seq` read with --camera `camera` to its end, with cfg and the
 *  description's colour readout and depth-noise model. */
inline TPipelineRun runPipeline(
    const std::string& seq, const std::string& camera, graphslam::CSlamContext::TConfig cfg)
{
  auto source = io::CFrameSource::open(seq, camera);
  TPipelineRun run;
  run.sensorSource = source->sensor().source;
  cfg.frontEnd.rolling_shutter_ms = source->sensor().sensor.frameReadoutMs();
  cfg.frontEnd.depth_noise = source->sensor().sensor.depth_noise;
  const auto gt = io::loadTumTrajectory(*source->groundTruthFile());
  graphslam::CSlamPipeline p(cfg, std::move(source));
  while (p.step())
  {
  }
  p.finish();
  run.trajectory = p.trajectory();
  run.ate = evaluation::CTrajectoryEvaluator().evaluate(gt, run.trajectory).ate;
  const auto& keyframes = p.context().odometry().keyframes();
  run.edgeChi2 = evaluation::edgeChi2(
      p.graph(), [&](mrpt::graphs::TNodeID id) { return keyframes.at(id).timestamp; }, gt);
  run.frontEndStats = p.context().odometry().stats();
  return run;
}

/** ORB, 600 features. */
inline graphslam::CSlamContext::TConfig orbConfig()
{
  graphslam::CSlamContext::TConfig cfg;
  cfg.frontEnd.extractor.feature_type = features::EFeatureType::ORB;
  cfg.frontEnd.extractor.max_features = 600;
  return cfg;
}

/** runPipeline with orbConfig(). */
inline TPipelineRun runOrbPipeline(const std::string& seq, const std::string& camera)
{
  return runPipeline(seq, camera, orbConfig());
}
}  // namespace roislam::testing
