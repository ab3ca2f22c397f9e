/* Frame source reading OpenNI2 itself: an .oni recording (OpenNI2's file
 * driver) or a live device ("openni2" = the first one, "openni2://<uri>" =
 * that device URI, e.g. as listed by OpenNI2's NiViewer). Both go through the
 * same code: one colour and one depth frame per next(), turned into an
 * observation (nextObservation(): raw depth, colour embedded, the sensor
 * description's cameras and extrinsics, as tum2rawlog writes it) and then into
 * a frame by observationToFrame(), which re-projects unregistered depth into
 * the colour camera. So a recording and the rawlog converted from it deliver
 * the same frames. Created by CFrameSource::open() for these inputs.
 *
 * The sensor description: the one given (a --camera value or the
 * <stem>.camera.ini beside the recording), else OpenNI2's own: intrinsics
 * from the streams' fields of view, registered depth when the device
 * registers it (a live device that can is switched to registration), no
 * rolling shutter. An unregistered recording without a description is an
 * error (the depth-to-colour extrinsics are not in the file; config/
 * sensor-kinect1.ini holds the Kinect v1 factory values). Depth units come
 * from the depth stream's pixel format (1 mm or 100 um), the frame rate from
 * its video mode. Colour must be RGB888 (the Kinect's and Xtion's mode).
 * Mirrored streams (OpenNI 1's default; the shared Kinect recording is one)
 * are flipped back into camera images; a live device is asked for unmirrored
 * streams. Timestamps: OpenNI2's, in seconds (a recording starts near 0).
 * Two sources playing one recording at the same time disturb OpenNI2's file
 * driver (frames time out): read a recording with one source at a time.
 * A description with estimate_registration has a recording's registration
 * estimated from its own frames first (CDepthColourCalibrator), as a
 * folder's; not a live device's.
 * Errors (no device, unreadable recording, a description that does not fit
 * the streams) throw std::runtime_error naming the input in one line.
 */
#pragma once

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <roislam/io/CFrameSource.h>

#include <memory>
#include <optional>
#include <string>

namespace roislam::io
{
class COpenNI2FrameSource : public CFrameSource
{
 public:
  /** True for "openni2" and "openni2://<uri>" (live devices). */
  static bool isDeviceSpec(const std::string& input);

  /** Opens `input` (an .oni file, "openni2" or "openni2://<uri>") with
   *  `sensor` (nullopt: OpenNI2's own description, see above). */
  COpenNI2FrameSource(const std::string& input, const std::optional<TSensorChoice>& sensor);
  ~COpenNI2FrameSource() override;

  std::optional<TRGBDFrame> next() override;
  /** Restarts a recording; a live device just goes on. */
  void rewind() override;
  /** Frames of a recording (the shorter stream); 0 for a live device. */
  std::size_t size() const override { return m_count; }
  const mrpt::img::TCamera& camera() const override { return m_sensor.sensor.colour; }
  /** <stem>.groundtruth.txt beside a recording, if any. */
  std::optional<std::string> groundTruthFile() const override;
  std::string name() const override;

  /** The next colour/depth pair as an observation (raw 16-bit depth on the
   *  depth camera's grid, colour embedded as BGR), nullptr at the end of a
   *  recording; advances like next(). */
  mrpt::obs::CObservation3DRangeScan::Ptr nextObservation();
  bool isLive() const { return m_live; }

 private:
  struct TStreams;
  void openDevice();
  /** With estimate_registration (and unregistered depth), for a recording:
   *  estimates the registration from up to kRegistrationFrames frames of its
   *  first kRegistrationScan (CDepthColourCalibrator), takes it when
   *  accepted, adds its summary to the sensor choice's reason, and rewinds. */
  void estimateRegistration();
  static constexpr std::size_t kRegistrationFrames = 40;
  static constexpr std::size_t kRegistrationScan = 400;
  TSensorChoice describe(const std::optional<TSensorChoice>& given) const;

  std::string m_input;
  bool m_live = false;
  std::size_t m_count = 0;
  std::size_t m_delivered = 0;
  std::unique_ptr<TStreams> m_streams;
};
}  // namespace roislam::io
