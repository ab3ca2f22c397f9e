/* Someone watching a SLAM run as it goes (the live view, libs/gui): the
 * driver of the run calls it once at the start, after every frame and after
 * every optimisation, and asks it between frames whether to stop. The
 * algorithm libraries know only this interface, never a window: headless
 * runs pass no observer and pay nothing.
 *
 * Called on the SLAM thread, so an observer copies what it needs and
 * returns: the references are valid during the call only. onFrame() may
 * block (the live view's pause). Drivers: CSlamPipeline (roi-graphslam's
 * loop; CRoiGraphSlamApp polls stopRequested()), and any other driver of our
 * deciders (MRPT's engine) can call the same hooks.
 */
#pragma once

#include <roislam/frontend/TFrameResult.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TRGBDFrame.h>

#include <string>

namespace roislam::graphslam
{
class CSlamObserver
{
 public:
  virtual ~CSlamObserver() = default;

  /** Once, before the first frame: the sequence (name, ground-truth file)
   *  and the context (configuration). */
  virtual void onStart(const io::CFrameSource& source, const CSlamContext& context) {}

  /** Where files the observer writes for the run (the live view's key-press
   *  screenshots) go: before the first frame, the run's staging folder
   *  (renamed into place with the outputs, CSlamRunner); after the outputs
   *  are written, the output folder itself. */
  virtual void onOutputFolder(const std::string& dir) {}

  /** After a frame went through the front end and the back end: its
   *  result, the decoded frame (colour, depth) and the context (keyframe
   *  clouds, loop closures, the front end's features and counts). */
  virtual void onFrame(
      const frontend::TFrameResult& result, const io::TRGBDFrame& frame,
      const CSlamContext& context) = 0;

  /** After an optimisation moved the keyframes: the graph's node poses
   *  (node id == keyframe id); closures found to be outliers are gone from
   *  context.loopClosures(). */
  virtual void onOptimized(const TGraph& graph, const CSlamContext& context) = 0;

  /** Polled between frames: true ends the run early, its outputs still
   *  written for the frames processed. */
  virtual bool stopRequested() const { return false; }
};
}  // namespace roislam::graphslam
