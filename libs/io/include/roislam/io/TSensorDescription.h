/* What roislam knows about an RGB-D sensor, beside the colour intrinsics: the
 * depth camera and its pose when depth is not registered to colour, the depth
 * scale, the colour camera's rolling-shutter readout, the depth-noise model
 * and the frame rate. The mode configs hold algorithm settings only; camera
 * facts live here. Presets fr1, fr2, fr3, icl, 7scenes, ros (sensorPreset()); files are an
 * MRPT ini (a TUM-layout folder may carry one as camera.ini, a rawlog or .oni
 * one as <stem>.camera.ini; rgbd-simul and tum2rawlog write one). Resolved by
 * resolveSensor() (CameraPresets.h), held by every frame source
 * (CFrameSource::sensor()), which registers unregistered depth with it; the
 * front end takes its readout (CRoiGraphSlamApp).
 *
 * File layout (MRPT ini):
 *   [CAMERA_PARAMS]        colour camera, mrpt::img::TCamera keys (resolution,
 *                          cx, cy, fx, fy, dist, distortion_model); required.
 *                          fx or fy may be negative: an image axis running
 *                          against the optical frame's (ICL-NUIM's fy < 0,
 *                          whose ground truth is a y-up camera's path); the
 *                          sources then flip the images (CameraAxes.h)
 *   [DEPTH_CAMERA_PARAMS]  depth camera, same keys; required when
 *                          depth_registered = false, ignored otherwise; its
 *                          fx and fy have the colour camera's signs (one axis
 *                          convention for both optical frames)
 *   [SensorDescription]    optional: a file with only [CAMERA_PARAMS] is a
 *                          plain calibration and gets the defaults below.
 *                          Every key optional; unknown keys are an error.
 *     key                        type / range                 default
 *     name                       non-empty string             file stem
 *         shown in logs and summary.json
 *     depth_registered           bool                         true
 *         true: depth is already on the colour camera's pixel grid
 *     depth_pose_in_colour       [x y z yaw pitch roll]       [0 0 0 0 0 0]
 *         m, deg: the depth optical frame in the colour optical frame
 *         (MRPT CPose3D text); used when depth_registered = false
 *     estimate_registration      bool                         false
 *         true: the colour-depth calibration is not known (7-Scenes
 *         publishes the depth camera alone). A folder's or a recording's
 *         reader then estimates depth_pose_in_colour and the colour fx,
 *         fy, cx, cy from the sequence's own frames, starting from the
 *         values given, and uses the estimate when it is well determined
 *         and differs from them (CDepthColourCalibrator); the description
 *         it reads with then says false. Ignored when depth_registered =
 *         true, for live devices and by the rawlog reader (tum2rawlog
 *         writes a rawlog with the description it read with)
 *     depth_scale                double > 0                   5000
 *         raw depth units per metre (TUM PNG 5000, OpenNI mm 1000)
 *     rolling_shutter_ms         double in [0, 1000/frame_rate]  0
 *         colour readout from first to last row, ms; 0 = global shutter
 *     rolling_shutter_direction  top_to_bottom | bottom_to_top  top_to_bottom
 *     frame_rate                 double > 0                   30 (Hz)
 *     colour_time_offset_ms      double, |x| <= 1000/frame_rate  0
 *         when the colour image was taken, minus its stamp, ms (negative:
 *         before it): the time of its middle row, which the front end's
 *         poses refer to (the rolling shutter is rectified to it). A
 *         driver stamps a frame when it arrives, after its exposure and
 *         readout. The frame sources add it to each colour stamp, so the
 *         trajectories (and the ground truth read against them) carry the
 *         time the image shows. Measured against a ground truth's clock
 *         (README "When the colour image was taken"); 0 = the stamp
 *     regular_frame_clock        bool                         true
 *         true: the camera takes its frames on a regular clock at about
 *         frame_rate, and the stamps (arrival times) jitter around it. The
 *         frame sources then time each frame by the clock fitted to the
 *         recent stamps (CFrameClock; it keeps a frame's stamp wherever the
 *         stamps stop following a clock). false: the stamps are the
 *         frames' times (a camera triggered at irregular times)
 *     common_pixel_sigma_px      double >= 0                  0 (px)
 *         1-sigma, per image axis, of an error that moves all keypoints of
 *         one colour image alike (what a frame keeps of its timing,
 *         rolling-shutter and calibration errors); it does not average
 *         down with the keypoint count, so the edge information carries it
 *         as its own term (0 = none: a rendered camera)
 *     keypoint_sigma_px          double >= 0                  0 (px)
 *         1-sigma, per image axis, of what the camera adds to each
 *         keypoint's own noise (motion blur, compression, sensor noise
 *         beyond a rendered image's), whatever its detection scale; added in
 *         quadrature to the detector's share (features::finestScaleSigmaPx;
 *         0 = none: a rendered camera)
 *     keypoint_time_sigma_ms     double in [0, 1000/frame_rate]  0
 *         1-sigma uncertainty of the time each keypoint is seen at, ms:
 *         its image motion over that time (the camera's velocity at the
 *         frame, the keypoint's depth) adds to its noise in quadrature.
 *         On a real camera it stands for errors that grow with the motion
 *         (on fr1 neither a rendered blur nor the colour-depth timing:
 *         README "Keypoint noise that follows the motion"; 0 = none: a
 *         rendered camera)
 *     depth_noise_model          kinect | disparity | none    kinect
 *     depth_noise_a              double >= 0                  0.0012 (m)
 *     depth_noise_b              double >= 0                  0.0019 (1/m)
 *     depth_noise_z0             double >= 0                  0.4 (m)
 *         kinect: sigma(z) = a + b (z - z0)^2
 *     disparity_bf               double > 0                   43.125 (m px)
 *         disparity: z = bf / d (baseline x focal; Kinect v1 7.5 cm x 575 px)
 *     disparity_steps_per_px     double > 0                   8
 *         disparity quantisation steps per pixel
 *     disparity_noise_steps      double >= 0                  0.1667
 *         disparity noise sigma, in steps
 *     lateral_sigma_px           double >= 0                  0.5 (px)
 *         jitter of the depth lookup
 * A bad value throws std::invalid_argument "[<section>] <key>: ..."; file
 * readers prefix the file name.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/img/TCamera.h>
#include <mrpt/poses/CPose3D.h>

#include <string>

namespace roislam::io
{
struct TSensorDescription : public mrpt::config::CLoadableOptions
{
  /** How the depth readings scatter around the truth. */
  struct TDepthNoise
  {
    std::string model = "kinect";  //!< kinect | disparity | none
    double a = 0.0012, b = 0.0019, z0 = 0.4;
    double disparity_bf = 43.125, disparity_steps_per_px = 8, disparity_noise_steps = 1.0 / 6;
    double lateral_sigma_px = 0.5;

    /** 1-sigma axial depth error at depth z (m): kinect a + b (z - z0)^2;
     *  disparity: the noise and the quantisation step (its uniform sigma,
     *  step / sqrt(12)) carried to depth (dz = z^2 / bf dd); none: 0. */
    double sigma(double z) const;
  };

  std::string name = "ros";
  mrpt::img::TCamera colour;  //!< [CAMERA_PARAMS]
  bool depth_registered = true;
  mrpt::img::TCamera depth;                   //!< [DEPTH_CAMERA_PARAMS], when !depth_registered
  mrpt::poses::CPose3D depth_pose_in_colour;  //!< depth optical frame in the colour optical frame
  /** The calibration between colour and depth is to be estimated from the
   *  frames (the given one is a start). */
  bool estimate_registration = false;
  double depth_scale = 5000;      //!< raw units per metre
  double rolling_shutter_ms = 0;  //!< readout of all rows, >= 0
  bool rolling_shutter_bottom_to_top = false;
  double frame_rate = 30;             //!< Hz
  double colour_time_offset_ms = 0;   //!< colour image's time minus its stamp, ms
  bool regular_frame_clock = true;    //!< frames on a regular clock; stamps jitter
  double common_pixel_sigma_px = 0;   //!< per-image keypoint shift, 1 sigma per axis
  double keypoint_sigma_px = 0;       //!< the camera's per-keypoint noise, 1 sigma per axis
  double keypoint_time_sigma_ms = 0;  //!< keypoint timing noise, ms (x image speed: px)
  TDepthNoise depth_noise;

  /** The readout as declared: positive top to bottom, negative bottom to
   *  top (CRgbdOdometry's rolling_shutter_ms convention). */
  double signedReadoutMs() const;
  /** The readout as it runs in the frames the sources deliver, the front
   *  end's rolling_shutter_ms: signedReadoutMs(), reversed for a colour
   *  camera with fy < 0, whose images the sources flip (CameraAxes.h). */
  double frameReadoutMs() const;

  /** Throws std::invalid_argument "[<section>] <key>: ..." on a bad value. */
  void validate(const std::string& section = "SensorDescription") const;
  /** Reads [CAMERA_PARAMS], [SensorDescription] (keys optional, unknown
   *  keys rejected) and, when unregistered, [DEPTH_CAMERA_PARAMS]; `section`
   *  names the scalar keys' section. */
  void loadFromConfigFile(
      const mrpt::config::CConfigFileBase& cfg, const std::string& section) override;
  /** Writes every key (the depth camera only when unregistered). */
  void saveToConfigFile(
      mrpt::config::CConfigFileBase& cfg, const std::string& section) const override;

  /** The whole description as ini text (saveToConfigFile into memory). */
  std::string toIniText() const;
};

/** "SensorDescription": the section of the scalar keys. */
const char* sensorSection();
}  // namespace roislam::io
