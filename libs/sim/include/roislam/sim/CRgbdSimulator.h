/* Synthetic RGB-D sequences with exact ground truth, for tests and demos.
 *
 * Renders a CSceneModel room offscreen (MRPT CFBORender, headless through EGL)
 * along a closed CCameraPath, corrupts the frames with CKinectNoiseModel, and
 * writes the TUM benchmark layout. Used by the rgbd-simul app and by tests that
 * need frames with known poses.
 *
 * Output folder (writeSequence):
 *   rgb/<stamp>.png     colour, 8-bit BGR PNG
 *   depth/<stamp>.png   depth, 16-bit PNG, metres x 5000, 0 = no reading
 *   rgb.txt, depth.txt  "timestamp filename" lists (TUM headers)
 *   groundtruth.txt     "timestamp tx ty tz qx qy qz qw", colour optical centre in the world
 *   accelerometer.txt   "timestamp ax ay az", one sample per frame: the specific
 *                       force (motion and gravity, m/s^2) in the TUM Kinect's
 *                       accelerometer axes (io/TumAccelerometer.h), with
 *                       0.05 m/s^2 noise per axis when noise is on
 *   camera.ini          the sensor description (io::TSensorDescription): [CAMERA_PARAMS]
 *                       colour intrinsics (mrpt::img::TCamera), [SensorDescription]
 *                       readout, depth scale, noise model, frame rate and, for
 *                       unregistered depth, [DEPTH_CAMERA_PARAMS] and the depth
 *                       camera's pose; read by roislam::io
 *   simulator.ini       [RgbdSimulator] options used
 * With layout = 7scenes, the folder is Microsoft 7-Scenes' own layout
 * instead (io/SevenScenes.h): frame-NNNNNN.color.png, frame-NNNNNN.depth.png
 * (millimetres, 65535 = no reading) and frame-NNNNNN.pose.txt (the 4x4
 * camera-to-world matrix of the depth camera, as KinectFusion gives it), no
 * lists, no timestamps, no camera.ini (the reader takes the 7scenes preset,
 * which config/rgbd-simul-7scenes.ini renders), and simulator.ini.
 * The folder is complete or absent (common::COutputFolder: a staging folder
 * beside it, renamed at the end).
 *
 * Ini section [RgbdSimulator] (every key optional; defaults in brackets):
 *   scene              textured | featureless                         [textured]
 *   furniture          furnish the room (bool): chairs, a table, a    [false]
 *                      shelf, a cabinet, more desk objects and tilted
 *                      panels (CSceneModel); textured or plain with scene
 *   layout             tum | 7scenes (output layout, above)           [tum]
 *   frames             number of frames, >= 2                         [90]
 *   seed               noise seed (uint32)                            [1]
 *   texture_seed       seed of the procedural textures (uint32)       [1]
 *   noise              Kinect-like corruption on/off (bool)           [true]
 *   fps                frame rate, Hz, (0, 1000]                      [30]
 *   base_timestamp     stamp of frame 0, s                            [1000000000.0]
 *   depth_time_offset  depth stamp minus colour stamp, s, |.| < 0.02  [0.0]
 *                      the depth image is rendered at its own stamp, from
 *                      where the camera is then (as a Kinect v1 streams
 *                      depth and colour unsynchronised: fr1/xyz +-15 ms)
 *   stamp_delay        how much later than the images were taken    [0.0]
 *                      their stamps are written, s, in [0, 0.02) (a
 *                      driver stamps a frame when it arrives): rgb.txt and
 *                      depth.txt (and the file names) carry the true times
 *                      plus it, groundtruth.txt the true times; camera.ini
 *                      records colour_time_offset_ms = -1000 x it. TUM
 *                      layout only (7-Scenes' has no stamps)
 *   rolling_shutter_ms row readout time, top to bottom, ms            [25]
 *                      (0 = global shutter). Rows are rendered in bands of
 *                      8, each from the pose at its time; the middle row is
 *                      at the frame's stamp and ground truth. 25 is what the
 *                      shipped configs assume for the TUM Kinect.
 *   exposure_ms        colour exposure time, ms, in [0, frame period] [0]
 *                      (0 = none): each band's colour is the mean of
 *                      exposure_samples renders spread evenly over it,
 *                      centred on the band's time (motion blur); the depth
 *                      is the middle render's. camera.ini's
 *                      keypoint_time_sigma_ms stays 0: on a blurred ICL-like
 *                      loop the term made the ATE worse at every value
 *                      (README "Keypoint noise that follows the motion")
 *   exposure_samples   renders per exposure, odd, in [3, 63]           [9]
 *   common_shift_px    1-sigma, px per axis, of a shift of each frame's   [0]
 *                      colour image as a whole (drawn per frame; the depth
 *                      stays on its true grid): an error common to all of a
 *                      frame's keypoints, which camera.ini records as
 *                      common_pixel_sigma_px
 *   width, height      image size, px                                 [640, 480]
 *   fx, fy, cx, cy     pinhole intrinsics, px                         [517.3 516.5 318.6 255.3]
 *   colour_dist        colour lens distortion [k1 k2 p1 p2 k3] (OpenCV's [0 0 0 0 0]
 *                      model, as TCamera's dist; camera.ini records it).
 *                      The distorted image is resampled from a pinhole
 *                      render (zoomed out about the principal point when
 *                      the lens sees more); a rolling shutter's band time
 *                      follows the distorted row at the principal point's
 *                      column. Registered depth is distorted alike (on the
 *                      colour grid); an unregistered depth camera has none.
 *                      Must map the image one to one; not with
 *                      common_shift_px
 *   min_depth          no reading below, m                            [0.4]
 *   max_depth          no reading beyond, m (<= 13.1, PNG range)      [4.0]
 *   noise_model        kinect | disparity                             [kinect]
 *                      kinect: CKinectNoiseModel (axial Gaussian, edges dropped);
 *                      disparity: CDisparityNoiseModel (ICL-NUIM-like: jittered
 *                      lookup, disparity noise and quantisation)
 *   depth_noise_a      kinect: sigma(z) = a + b (z - z0)^2: a, m      [0.0012]
 *   depth_noise_b      b, 1/m                                         [0.0019]
 *   depth_noise_z0     z0, m                                          [0.4]
 *   edge_jump_ratio    kinect: relative 3x3 depth jump that drops a pixel [0.03]
 *   disparity_bf       disparity: baseline x focal, m px              [43.125]
 *   disparity_steps_per_px  disparity: quantisation steps per px      [8]
 *   disparity_noise_steps   disparity: noise sigma, steps             [0.16666666666666666]
 *   lateral_sigma_px   disparity: jitter of the depth lookup, px      [0.5]
 *   depth_registered   depth on the colour camera's grid (bool)       [true]
 *                      false: depth is rendered by its own camera (below), as
 *                      a Kinect delivers it before registration
 *   depth_fx, depth_fy, depth_cx, depth_cy  depth camera pinhole, px  [575.8 575.8 319.5 239.5]
 *                      (same image size as colour)
 *   depth_pose_in_colour  depth optical frame in the colour optical frame,
 *                      [x y z yaw pitch roll] m, deg (MRPT CPose3D)   [[-0.025 0 0 0 0 0]]
 *   depth_radial_bias  c: every depth reading is z (1 + c r^2), r^2 = [0]
 *                      ((u - cx) / fx)^2 + ((v - cy) / fy)^2 of the depth
 *                      image's own camera (the colour camera's for
 *                      registered depth), |c| <= 0.2. A bias fixed in the
 *                      image, as a Kinect v1 has (its depth distortion),
 *                      unknown to the reader: camera.ini does not record
 *                      it. Applied with noise off too. 0.03 reads 1.8 %
 *                      deep at the corners of a 640 x 480, 517 px image
 *   camera_y_up        publish the camera as ICL-NUIM does (bool)     [false]
 *                      true: camera.ini declares fy < 0 (and depth_fy < 0),
 *                      the ground truth is the path of that y-up optical
 *                      frame (each pose P written as S P S, S = diag(1, -1,
 *                      1): a mirrored world), depth_pose_in_colour and the
 *                      accelerometer's y axis likewise; the images are the
 *                      same. The readers turn it back (io/CameraAxes.h)
 *   rgb_noise_std      colour noise, grey levels                      [2.0]
 *   supersampling      render ss x ss samples per pixel, 1..4         [2]
 *                      (colour: block mean; depth stays exact at pixel centres)
 *   texels_per_metre   wall texture density (objects 2.5x), [50,3000] [600]
 *   path_translation_amplitude  lateral half-extent of the loop, m    [0.3]
 *   path_yaw_amplitude_deg, path_pitch_amplitude_deg,
 *   path_roll_amplitude_deg     rotation wobble, deg                  [25, 5, 4]
 *   max_linear_speed   path speed limit, m/s (amplitudes shrink)      [0.5]
 *   max_angular_speed_deg  path angular speed limit, deg/s            [60]
 * Noise off keeps the range limits but drops noise and edge dropout.
 * A malformed value, a value out of range or an unknown key throws
 * std::invalid_argument naming "[RgbdSimulator] <key>".
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/img/TCamera.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/system/COutputLogger.h>
#include <roislam/io/TSensorDescription.h>

#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>

#include "roislam/sim/CCameraPath.h"
#include "roislam/sim/CSceneModel.h"

namespace roislam::sim
{
namespace detail
{
struct TDistortionMap;
}

class CRgbdSimulator : public mrpt::system::COutputLogger
{
 public:
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    std::string scene = "textured";
    bool furniture = false;
    std::string layout = "tum";
    unsigned frames = 90;
    uint32_t seed = 1;
    uint32_t textureSeed = 1;
    bool noise = true;
    double fps = 30.0;
    double baseTimestamp = 1000000000.0;
    double depthTimeOffset = 0.0;
    double stampDelay = 0.0;
    double rollingShutterMs = 25.0;
    double exposureMs = 0.0;
    unsigned exposureSamples = 9;
    double commonShiftPx = 0.0;
    unsigned width = 640, height = 480;
    double fx = 517.3, fy = 516.5, cx = 318.6, cy = 255.3;
    std::string colourDist = "[0 0 0 0 0]";
    double minDepth = 0.4, maxDepth = 4.0;
    double depthNoiseA = 0.0012, depthNoiseB = 0.0019, depthNoiseZ0 = 0.4;
    double edgeJumpRatio = 0.03;
    std::string noiseModel = "kinect";
    double disparityBf = 43.125, disparityStepsPerPx = 8, disparityNoiseSteps = 1.0 / 6;
    double lateralSigmaPx = 0.5;
    bool depthRegistered = true;
    double depthFx = 575.8, depthFy = 575.8, depthCx = 319.5, depthCy = 239.5;
    std::string depthPoseInColour = "[-0.025 0 0 0 0 0]";
    double depthRadialBias = 0.0;
    bool cameraYUp = false;
    double rgbNoiseStd = 2.0;
    unsigned supersampling = 2;
    double texelsPerMetre = 600.0;
    double pathTranslationAmplitude = 0.3;
    double pathYawAmplitudeDeg = 25, pathPitchAmplitudeDeg = 5, pathRollAmplitudeDeg = 4;
    double maxLinearSpeed = 0.5, maxAngularSpeedDeg = 60;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& cfg, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& cfg, const std::string& section) const override;
    /** Throws std::invalid_argument "[section] key: ..." on a bad value. */
    void validate(const std::string& section = "RgbdSimulator") const;
  };

  struct TFrame
  {
    std::size_t index = 0;
    double timestamp = 0, depthTimestamp = 0;
    mrpt::poses::CPose3D pose;  //!< colour optical frame in the world (ground truth)
    cv::Mat rgb;                //!< CV_8UC3 BGR
    /** CV_32FC1 metres, 0 = no reading (not yet quantised), on the depth
     *  camera's grid (depthCamera(); the colour grid when registered). */
    cv::Mat depth;
    /** The colour image's common shift (common_shift_px), px: its content
     *  sits this far right / down of where the camera's intrinsics put it. */
    cv::Point2d colourShiftPx;
  };

  struct TWriteStats
  {
    std::size_t frames = 0;
    double renderSeconds = 0;  //!< rendering and noise
    double writeSeconds = 0;   //!< PNG encoding and files
    double totalSeconds = 0;   //!< including scene construction
  };

  /** Validates the options and builds the scene and the path (no OpenGL yet). */
  explicit CRgbdSimulator(const TOptions& options);
  ~CRgbdSimulator() override;
  CRgbdSimulator(const CRgbdSimulator&) = delete;
  CRgbdSimulator& operator=(const CRgbdSimulator&) = delete;

  const TOptions& options() const { return m_opts; }
  /** Intrinsics of the written colour images (integer pixel centres, TUM convention). */
  mrpt::img::TCamera camera() const;
  /** Intrinsics of the written depth images: camera() when depth is
   *  registered, else the depth camera's. */
  mrpt::img::TCamera depthCamera() const;
  /** The depth camera's optical frame in the colour optical frame (identity
   *  when registered). */
  mrpt::poses::CPose3D depthPoseInColour() const;
  /** What camera.ini holds: the sensor that rendered the sequence (with
   *  camera_y_up, in the y-up convention: fy < 0). */
  io::TSensorDescription sensorDescription() const;
  /** A pose as the sequence publishes it: unchanged, or with camera_y_up
   *  in the y-up convention (S P S, S = diag(1, -1, 1)). */
  mrpt::poses::CPose3D published(const mrpt::poses::CPose3D& pose) const;
  const CSceneModel& scene() const { return m_scene; }
  const CCameraPath& path() const { return m_path; }

  double timestamp(std::size_t i) const;
  /** Depth PNG value per metre of the written sequences (TUM: 5000). */
  static constexpr double kDepthScale = 5000.0;

  /** Rows per render: 8 with a rolling shutter, else the image height. */
  unsigned bandHeight() const;
  /** Ground-truth pose of frame i (colour optical frame in the world). */
  mrpt::poses::CPose3D groundTruthPose(std::size_t i) const;
  /** What the Kinect's accelerometer reads at frame i, without noise:
   *  gravity (world z up, 9.81 m/s^2) plus the path's acceleration, as a
   *  specific force in the accelerometer's axes. */
  mrpt::math::TVector3D accelerometerReading(std::size_t i) const;

  /** Renders frame i (0 <= i < frames); noise per options, deterministic in
   *  (seed, i). The OpenGL (EGL) context is created on first call, in this
   *  thread; that call also sets MRPT_FBORENDER_USE_LUT=false in the process
   *  environment so MRPT returns exact linear depth. Only one simulator per thread
   *  may render at a time (MRPT keeps GL state per thread): rendering with a
   *  second one while the first is alive throws std::logic_error. */
  TFrame renderFrame(std::size_t i);

  /** Renders every frame and writes the TUM layout to outDir (see above).
   *  An existing outDir must be empty, or with `overwrite` an earlier output
   *  of this class (which it replaces); throws std::runtime_error naming the
   *  path otherwise. */
  TWriteStats writeSequence(const std::string& outDir, bool overwrite = false);

 private:
  struct Impl;
  struct TBands;
  /** The frame's bands rendered from (band pose (+) offset) with the pinhole
   *  fx, fy, cx, cy (output pixels), supersampled; dt seconds after the
   *  frame's colour time (the depth's depth_time_offset). With exposed, the
   *  colour is exposed over exposure_ms (motion blur; the depth stays the
   *  band time's). colourLens: the colour pinhole of a distorted colour
   *  image (its rows' times through readoutRow()). */
  TBands renderBands(
      std::size_t i, const mrpt::poses::CPose3D& offset, double fx, double fy, double cx, double cy,
      double dt = 0, bool exposed = false, bool colourLens = false);
  /** The frame's colour image into rgb (CV_8UC3, through the lens if
   *  any; shifted by common_shift_px), and its bands (the registered depth's
   *  when the stamps agree). */
  TBands renderColour(std::size_t i, double shiftX, double shiftY, cv::Mat& rgb);
  /** Where the distorted colour image finds its content (made once). */
  const detail::TDistortionMap& lensMap() const;
  /** The output row whose readout time a render row of the colour pinhole
   *  has (itself unless the colour is distorted). */
  double readoutRow(double renderRow) const;
  /** depth_radial_bias on a rendered depth image (metres, CV_32F). */
  void applyRadialBias(cv::Mat& depth) const;
  /** depth_radial_bias, range limits and the options' noise model on a
   *  rendered frame. */
  void corrupt(TFrame& f, std::size_t i) const;
  TOptions m_opts;
  CSceneModel m_scene;
  CCameraPath m_path;
  std::unique_ptr<Impl> m_impl;
};
}  // namespace roislam::sim
