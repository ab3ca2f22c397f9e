/* Test helper: runs CRgbdOdometry over a frame source and evaluates the
 * odometry-only trajectory (every frame's pose) against ground truth. */
#pragma once

#include <roislam/common/ProcessTuning.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>

#include <chrono>
#include <deque>
#include <string>
#include <vector>

namespace roislam::frontend::testing
{
struct TRunSummary
{
  io::TTrajectory trajectory;
  std::vector<TFrameResult> results;
  CRgbdOdometry::TStats stats;
  std::deque<TKeyframe> keyframes;
  double wallSeconds = 0;     //!< whole loop incl. image decoding
  double processMs = 0;       //!< sum of process() times
  std::optional<double> ate;  //!< ATE RMSE (m) when ground truth exists
};

inline TRunSummary runOdometry(
    const std::string& dir, const CRgbdOdometry::TOptions& options, std::size_t maxFrames = 0,
    bool initialFromGroundTruth = true)
{
  // As the apps do, so that the printed speeds compare with theirs.
  common::tuneAllocatorForImages();
  TRunSummary s;
  auto src = io::CFrameSource::open(dir);
  io::TTrajectory gt;
  if (auto g = src->groundTruthFile())
    gt = io::loadTumTrajectory(*g);
  CRgbdOdometry odo(options);
  const auto t0 = std::chrono::steady_clock::now();
  bool first = true;
  while (auto f = src->next())
  {
    if (maxFrames && s.results.size() >= maxFrames)
      break;
    if (first && initialFromGroundTruth && !gt.empty())
    {
      // The ground-truth pose closest in time, so trajectories compare directly.
      const auto* best = &gt.front();
      for (const auto& p : gt)
        if (std::abs(p.timestamp - f->timestamp) < std::abs(best->timestamp - f->timestamp))
          best = &p;
      odo.setInitialPose(best->pose);
    }
    first = false;
    auto r = odo.process(*f);
    s.processMs += r.times.total_ms;
    if (r.pose)
      s.trajectory.push_back({r.timestamp, *r.pose});
    s.results.push_back(std::move(r));
  }
  s.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.stats = odo.stats();
  s.keyframes = odo.keyframes();
  if (!gt.empty() && s.trajectory.size() >= 3)
    s.ate = evaluation::CTrajectoryEvaluator().evaluate(gt, s.trajectory).ate.rmse;
  return s;
}
}  // namespace roislam::frontend::testing
