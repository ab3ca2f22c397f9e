/* Frame source reading a TUM RGB-D benchmark folder directly (rgb.txt,
 * depth.txt, rgb/, depth/), without converting it to a rawlog first.
 *
 * Colour and depth streams are paired like the benchmark's associate.py
 * (|dt| < maxTimeDifference, greedy one-to-one by smallest difference, see
 * associateStamps()); colour frames without a partner are skipped and counted.
 * Images are read lazily, one frame per next(). Created by CFrameSource::open()
 * and used directly by tum2rawlog (entries(), readColourImage(), readDepthImage()).
 * A 7-Scenes sequence folder (frame-NNNNNN.color/depth.png and .pose.txt, no
 * rgb.txt; SevenScenes.h) is read too: frame i at i / frame_rate, its poses as
 * the ground truth (groundTruthFile(): a TUM file of the colour camera's
 * poses, written to a temporary folder that lives as long as the source).
 * Depth readings of 65535 mean "none" (7-Scenes) in every folder.
 * With a sensor description whose depth is not registered (e.g. a 7-Scenes-like
 * rgbd-simul folder), depth PNGs are on the depth camera's grid and next()
 * re-projects them into the colour camera (registerDepthToColour()); one
 * that asks for it (estimate_registration) has its registration estimated
 * from 40 frames spread over the sequence first (CDepthColourCalibrator).
 *
 * ini section [TumFrameSource] (TOptions):
 *   max_time_difference  double  0.02    s    colour/depth association window
 *   depth_scale          double  5000    1/m  depth PNG value per metre (TUM: 5000);
 *                                             a sensor description's depth_scale replaces it
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <roislam/io/CFrameSource.h>

#include <string>
#include <utility>
#include <vector>

namespace roislam::io
{
class CTumFrameSource : public CFrameSource
{
 public:
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    double maxTimeDifference = 0.02;  //!< s
    double depthScale = 5000;         //!< raw depth units per metre

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& cfg, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& cfg, const std::string& section) const override;
  };

  /** One associated colour/depth pair; file names are absolute paths. */
  struct TEntry
  {
    double rgbStamp = 0;
    double depthStamp = 0;
    std::string rgbFile;
    std::string depthFile;
    /** When the colour image was taken (CFrameSource::colourTime of the
     *  stamps in order): the frame's timestamp. */
    double time = 0;
  };

  /** Reads and associates rgb.txt/depth.txt of `dir` and checks that every
   *  listed image exists (images themselves are read in next()). The camera's
   *  ncols/nrows must match the images. Throws std::runtime_error naming the
   *  folder, file or file:line on bad input. */
  CTumFrameSource(
      const std::string& dir, const mrpt::img::TCamera& camera, const TOptions& options);
  /** As above with default TOptions. */
  CTumFrameSource(const std::string& dir, const mrpt::img::TCamera& camera);
  /** Reads `dir` with a sensor description (sensor() returns `choice`): its
   *  colour intrinsics, its depth_scale (replacing options.depthScale) and,
   *  when its depth is not registered, its depth camera and
   *  depth_pose_in_colour. */
  CTumFrameSource(const std::string& dir, const TSensorChoice& choice, const TOptions& options);

  /** Removes the ground truth written for a 7-Scenes folder. */
  ~CTumFrameSource() override;
  CTumFrameSource(const CTumFrameSource&) = delete;
  CTumFrameSource& operator=(const CTumFrameSource&) = delete;

  std::optional<TRGBDFrame> next() override;
  void rewind() override { m_next = 0; }
  void seek(std::size_t index) override;
  std::size_t size() const override { return m_entries.size(); }
  /** The colour camera as the frames carry it: the description's, with
   *  positive focal lengths (CameraAxes.h). */
  const mrpt::img::TCamera& camera() const override { return m_camera; }
  std::optional<std::string> groundTruthFile() const override;
  std::optional<std::string> accelerometerFile() const override;
  std::string name() const override;
  std::size_t skippedFrames() const override { return m_skipped; }

  /** The associated pairs in colour-time order. */
  const std::vector<TEntry>& entries() const { return m_entries; }
  /** Absolute path of the dataset folder. */
  const std::string& directory() const { return m_dir; }
  const TOptions& options() const { return m_options; }

  /** Reads a colour image as CV_8UC3 BGR; throws "<file>: ..." when missing,
   *  undecodable or not camera.ncols x camera.nrows. */
  static cv::Mat readColourImage(const std::string& file, const mrpt::img::TCamera& camera);
  /** Reads a depth PNG as raw CV_16UC1; throws "<file>: ..." when missing,
   *  undecodable, not single-channel 16-bit or not of `camera`'s size (the
   *  depth camera's when depth is not registered). */
  static cv::Mat readDepthImage(const std::string& file, const mrpt::img::TCamera& camera);

 private:
  std::string m_dir;
  /** The frames' cameras: the description's with positive focal lengths. */
  mrpt::img::TCamera m_camera;
  mrpt::img::TCamera m_depthCamera;  //!< the grid of the depth PNGs
  TOptions m_options;
  std::vector<TEntry> m_entries;
  std::size_t m_skipped = 0;
  std::size_t m_next = 0;
  /** A 7-Scenes folder's ground truth as a TUM file (its own temporary
   *  folder, removed by the destructor); empty otherwise. */
  std::string m_groundTruthTemp;

  /** The frames and ground truth of a 7-Scenes folder (SevenScenes.h). */
  void readSevenScenesFolder();
  /** Frames read for estimate_registration, evenly over the sequence. */
  static constexpr std::size_t kRegistrationFrames = 40;
  /** With estimate_registration (and unregistered depth): estimates the
   *  registration from the frames (CDepthColourCalibrator), takes it when
   *  accepted, and adds its summary to the sensor choice's reason. */
  void estimateRegistration();
  /** Sets every entry's time. */
  void timeFrames();
  /** One entry's colour (BGR) and depth (metres, on the depth camera's
   *  grid, not registered), flipped to positive focal lengths. */
  std::pair<cv::Mat, cv::Mat> readRawFrame(const TEntry& e) const;
};
}  // namespace roislam::io
