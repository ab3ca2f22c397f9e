#include "roislam/sim/CRgbdSimulator.h"

#include <mrpt/img/CImage.h>
#include <mrpt/math/CMatrixF.h>
#include <mrpt/opengl/CCamera.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/random/RandomGenerators.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>
#include <vector>

#include "LensDistortion.h"
#include "roislam/io/TumAccelerometer.h"
#include "roislam/sim/CDisparityNoiseModel.h"
#include "roislam/sim/CKinectNoiseModel.h"

namespace roislam::sim
{
namespace
{
CCameraPath::TParams pathParams(const CRgbdSimulator::TOptions& o)
{
  CCameraPath::TParams p;
  p.translationAmplitude = o.pathTranslationAmplitude;
  p.yawAmplitudeDeg = o.pathYawAmplitudeDeg;
  p.pitchAmplitudeDeg = o.pathPitchAmplitudeDeg;
  p.rollAmplitudeDeg = o.pathRollAmplitudeDeg;
  p.maxLinearSpeed = o.maxLinearSpeed;
  p.maxAngularSpeedDeg = o.maxAngularSpeedDeg;
  return p;
}

const CRgbdSimulator::TOptions& validated(const CRgbdSimulator::TOptions& o)
{
  o.validate();
  return o;
}

/** The render camera of the band of bandRows output rows from row r0, ss x ss
 *  supersampled, for output intrinsics fx, fy, cx, cy. OpenGL samples pixel
 *  (u, v) at (u + 0.5, v + 0.5): the principal point is shifted so rays go
 *  through integer pixel centres as in MRPT/TUM; output pixel u is the block
 *  centred at ss * u + ss / 2. The band's frustum is the full image's cut to
 *  its rows: the principal point moves up by r0. */
mrpt::img::TCamera bandPinhole(
    double fx, double fy, double cx, double cy, unsigned ss, unsigned W, unsigned bandRows,
    unsigned r0)
{
  mrpt::img::TCamera pinhole;
  pinhole.ncols = W * ss;
  pinhole.nrows = bandRows * ss;
  pinhole.fx(fx * ss);
  pinhole.fy(fy * ss);
  pinhole.cx(cx * ss + ss / 2.0);
  pinhole.cy(cy * ss + ss / 2.0 - static_cast<double>(r0 * ss));
  return pinhole;
}

/** Depth at the centres of the W x H output pixels from a render supersampled
 *  ss x ss. Odd ss: the central sample. Even ss: the centre is the corner
 *  shared by the 2x2 central samples; on a plane inverse depth is affine in the
 *  image, so the mean of their inverse depths is exact there. Where the four
 *  samples are not coplanar (a discontinuity) the nearest one is kept, and a
 *  block touching "no reading" gives no reading. */
cv::Mat depthAtPixelCentres(const mrpt::math::CMatrixFloat& D, unsigned ss, unsigned W, unsigned H)
{
  cv::Mat out(H, W, CV_32FC1);
  for (unsigned r = 0; r < H; ++r)
  {
    auto* o = out.ptr<float>(r);
    for (unsigned c = 0; c < W; ++c)
    {
      if (ss % 2 == 1)
      {
        o[c] = D(ss * r + ss / 2, ss * c + ss / 2);
        continue;
      }
      const unsigned r0 = ss * r + ss / 2 - 1, c0 = ss * c + ss / 2 - 1;
      const float z00 = D(r0, c0), z01 = D(r0, c0 + 1), z10 = D(r0 + 1, c0),
                  z11 = D(r0 + 1, c0 + 1);
      if (z00 <= 0 || z01 <= 0 || z10 <= 0 || z11 <= 0)
      {
        o[c] = 0;
        continue;
      }
      const double w00 = 1.0 / z00, w01 = 1.0 / z01, w10 = 1.0 / z10, w11 = 1.0 / z11;
      const bool planar = std::abs(w00 + w11 - w01 - w10) <= 1e-4 * (w00 + w11);
      o[c] = planar ? static_cast<float>(4.0 / (w00 + w01 + w10 + w11))
                    : std::min(std::min(z00, z01), std::min(z10, z11));
    }
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------- simulator

namespace
{
// MRPT binds GL resources per thread, not per context: a second live renderer
// in the same thread silently renders garbage. One owner per thread is enforced.
thread_local const void* tGlOwner = nullptr;
}  // namespace

struct CRgbdSimulator::Impl
{
  mrpt::opengl::COpenGLScene::Ptr glScene;
  std::unique_ptr<mrpt::opengl::CFBORender> fbo;
  detail::TDistortion dist{};  //!< colour_dist
  /** Where the distorted colour image finds its content (made at the first
   *  render; none without distortion). */
  std::optional<detail::TDistortionMap> lens;
};

CRgbdSimulator::CRgbdSimulator(const TOptions& options)
    : mrpt::system::COutputLogger("CRgbdSimulator"),
      m_opts(validated(options)),
      m_scene(CSceneModel::build(
          CSceneModel::sceneTypeFromString(options.scene), options.textureSeed,
          options.texelsPerMetre, options.furniture)),
      m_path(pathParams(options), (options.frames - 1) / options.fps),
      m_impl(std::make_unique<Impl>())
{
  m_impl->dist = *detail::parseDistortion(m_opts.colourDist);  // validated
}

CRgbdSimulator::~CRgbdSimulator()
{
  if (m_impl && m_impl->fbo && tGlOwner == this)
  {
    m_impl->fbo.reset();
    m_impl->glScene.reset();
    tGlOwner = nullptr;
  }
}

mrpt::img::TCamera CRgbdSimulator::camera() const
{
  mrpt::img::TCamera c;
  c.ncols = m_opts.width;
  c.nrows = m_opts.height;
  c.fx(m_opts.fx);
  c.fy(m_opts.fy);
  c.cx(m_opts.cx);
  c.cy(m_opts.cy);
  c.dist.fill(0);
  std::copy(m_impl->dist.begin(), m_impl->dist.end(), c.dist.begin());
  if (!detail::isZero(m_impl->dist))
    c.distortion = mrpt::img::DistortionModel::plumb_bob;
  c.cameraName = "rgbd-simul";
  return c;
}

mrpt::img::TCamera CRgbdSimulator::depthCamera() const
{
  if (m_opts.depthRegistered)
    return camera();
  mrpt::img::TCamera c = camera();
  c.dist.fill(0);
  c.distortion = mrpt::img::DistortionModel::none;
  c.fx(m_opts.depthFx);
  c.fy(m_opts.depthFy);
  c.cx(m_opts.depthCx);
  c.cy(m_opts.depthCy);
  c.cameraName = "rgbd-simul depth";
  return c;
}

mrpt::poses::CPose3D CRgbdSimulator::depthPoseInColour() const
{
  mrpt::poses::CPose3D p;
  if (!m_opts.depthRegistered)
    p.fromString(m_opts.depthPoseInColour);
  return p;
}

mrpt::poses::CPose3D CRgbdSimulator::published(const mrpt::poses::CPose3D& pose) const
{
  if (!m_opts.cameraYUp)
    return pose;
  // S P S with S = diag(1, -1, 1): the same motion seen in a mirrored world
  // by a y-up optical frame (a proper rotation again: det(S R S) = det R).
  auto R = pose.getRotationMatrix();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if ((i == 1) != (j == 1))
        R(i, j) = -R(i, j);
  mrpt::math::CVectorFixedDouble<3> t;
  t[0] = pose.x();
  t[1] = -pose.y();
  t[2] = pose.z();
  return mrpt::poses::CPose3D(R, t);
}

io::TSensorDescription CRgbdSimulator::sensorDescription() const
{
  io::TSensorDescription d;
  d.name = "rgbd-simul";
  d.colour = camera();
  d.depth_registered = m_opts.depthRegistered;
  if (!m_opts.depthRegistered)
  {
    d.depth = depthCamera();
    d.depth_pose_in_colour = published(depthPoseInColour());
  }
  if (m_opts.cameraYUp)
  {
    // v = fy Y / Z + cy = (-fy) (-Y) / Z + cy: the same pixels, y up.
    for (mrpt::img::TCamera* c : {&d.colour, &d.depth})
      if (c->fy() > 0)
        c->setIntrinsicParamsFromValues(c->fx(), -c->fy(), c->cx(), c->cy());
  }
  d.depth_scale = kDepthScale;
  d.rolling_shutter_ms = m_opts.rollingShutterMs;
  d.common_pixel_sigma_px = m_opts.commonShiftPx;
  d.frame_rate = m_opts.fps;
  d.colour_time_offset_ms = -1000 * m_opts.stampDelay;
  auto& n = d.depth_noise;
  n.model = m_opts.noise ? m_opts.noiseModel : "none";
  n.a = m_opts.depthNoiseA;
  n.b = m_opts.depthNoiseB;
  n.z0 = m_opts.depthNoiseZ0;
  n.disparity_bf = m_opts.disparityBf;
  n.disparity_steps_per_px = m_opts.disparityStepsPerPx;
  n.disparity_noise_steps = m_opts.disparityNoiseSteps;
  n.lateral_sigma_px = m_opts.lateralSigmaPx;
  return d;
}

unsigned CRgbdSimulator::bandHeight() const
{
  // 8 rows: the camera turns at most 60 deg/s * 20 ms / 60 bands = 0.02 deg
  // within a band, a fifth of a pixel; the renders are 16 rows high and cheap.
  return m_opts.rollingShutterMs > 0 ? std::min(8u, m_opts.height) : m_opts.height;
}

double CRgbdSimulator::timestamp(std::size_t i) const
{
  // Whole microseconds, so the "%.6f" file names parse back to the same value.
  return m_opts.baseTimestamp + std::round(static_cast<double>(i) / m_opts.fps * 1e6) * 1e-6;
}

mrpt::poses::CPose3D CRgbdSimulator::groundTruthPose(std::size_t i) const
{
  return m_path.opticalPoseAt(static_cast<double>(i) / m_opts.fps);
}

mrpt::math::TVector3D CRgbdSimulator::accelerometerReading(std::size_t i) const
{
  // Second central difference of the (smooth, analytic) path.
  const double t = static_cast<double>(i) / m_opts.fps, h = 1e-3;
  const auto p0 = m_path.opticalPoseAt(t - h).translation();
  const auto p1 = m_path.opticalPoseAt(t).translation();
  const auto p2 = m_path.opticalPoseAt(t + h).translation();
  const mrpt::math::TVector3D accel = (p2 - p1 * 2.0 + p0) * (1.0 / (h * h));
  // An accelerometer at rest reads +g upwards (the specific force).
  const mrpt::math::TVector3D specificWorld = accel + mrpt::math::TVector3D(0, 0, 9.81);
  const mrpt::math::TVector3D optical = m_path.opticalPoseAt(t).inverseRotateVector(specificWorld);
  // The axis change is a half turn about z, its own inverse.
  return io::accelerometerToOptical(optical);
}

struct CRgbdSimulator::TBands
{
  cv::Mat rgbSS;                     //!< supersampled colour
  mrpt::math::CMatrixFloat depthSS;  //!< supersampled depth, m
};

double CRgbdSimulator::readoutRow(double renderRow) const
{
  if (!m_impl->lens)
    return renderRow;
  // The render's row at the principal point's column, through the lens.
  const double yUndistorted = (renderRow - m_opts.cy) / (m_opts.fy / m_impl->lens->zoom);
  return m_opts.fy * detail::distortNormalised(m_impl->dist, {0, yUndistorted}).y + m_opts.cy;
}

CRgbdSimulator::TBands CRgbdSimulator::renderBands(
    std::size_t i, const mrpt::poses::CPose3D& offset, double fx, double fy, double cx, double cy,
    double dt, bool exposed, bool colourLens)
{
  const unsigned ss = m_opts.supersampling;
  const unsigned W = m_opts.width, H = m_opts.height;
  auto& fbo = *m_impl->fbo;
  auto& glScene = *m_impl->glScene;
  // One render per band of rows, each from the camera pose at that band's
  // time (rolling shutter; one band = a global shutter). The band's frustum
  // is the full image's cut to its rows: the principal point moves up.
  const unsigned bandRows = bandHeight();
  const double tFrame = static_cast<double>(i) / m_opts.fps + dt;
  TBands out;
  out.rgbSS = cv::Mat(H * ss, W * ss, CV_8UC3);
  out.depthSS.setSize(H * ss, W * ss);
  for (unsigned r0 = 0; r0 < H; r0 += bandRows)
  {
    // Row y is read at t + (y / H - 0.5) * readout: the middle row at the
    // frame's stamp, where the ground truth is.
    const double yMid =
        colourLens ? readoutRow(r0 + (bandRows - 1) / 2.0) : r0 + (bandRows - 1) / 2.0;
    const double t = tFrame + (yMid / H - 0.5) * m_opts.rollingShutterMs * 1e-3;
    const mrpt::img::TCamera pinhole = bandPinhole(fx, fy, cx, cy, ss, W, bandRows, r0);
    const unsigned rows = std::min(bandRows, H - r0) * ss;
    const cv::Rect band(0, 0, static_cast<int>(W * ss), static_cast<int>(rows));
    const cv::Rect into(
        0, static_cast<int>(r0 * ss), static_cast<int>(W * ss), static_cast<int>(rows));
    // The band seen from the camera at time tb (the frame's ground-truth
    // pose itself for a global shutter's one band at the frame's time).
    const auto render =
        [&](double tb, bool atStamp, mrpt::img::CImage& img, mrpt::math::CMatrixFloat& range)
    {
      mrpt::opengl::CCamera cam;
      cam.set6DOFMode(true);
      cam.setPose(
          (bandRows == H && dt == 0 && atStamp ? groundTruthPose(i) : m_path.opticalPoseAt(tb)) +
          offset);
      cam.setProjectiveFromPinhole(pinhole);
      fbo.setCamera(glScene, cam);
      fbo.render_RGBD(glScene, img, range);
    };
    mrpt::img::CImage rgbImg;
    mrpt::math::CMatrixFloat depthM;
    // An exposed colour band is the mean of renders spread evenly over the
    // exposure, centred on the band's time; the middle one (an odd count)
    // is at that time and gives the depth.
    const unsigned n = exposed && m_opts.exposureMs > 0 ? m_opts.exposureSamples : 1;
    if (n == 1)
    {
      render(t, true, rgbImg, depthM);
      rgbImg.asCvMatRef()(band).copyTo(out.rgbSS(into));
    }
    else
    {
      cv::Mat sum = cv::Mat::zeros(band.size(), CV_32FC3), one;
      for (unsigned k = 0; k < n; ++k)
      {
        const bool middle = 2 * k + 1 == n;
        mrpt::img::CImage kRgb;
        mrpt::math::CMatrixFloat kDepth;
        render(t + ((k + 0.5) / n - 0.5) * m_opts.exposureMs * 1e-3, middle, kRgb, kDepth);
        kRgb.asCvMatRef()(band).convertTo(one, CV_32FC3, 1.0 / n);
        sum += one;
        if (middle)
          depthM = kDepth;
      }
      cv::Mat dst = out.rgbSS(into);  // same size and type: written in place
      sum.convertTo(dst, CV_8UC3);
    }
    out.depthSS.asEigen().block(r0 * ss, 0, rows, W * ss) =
        depthM.asEigen().block(0, 0, rows, W * ss);
  }
  return out;
}

void CRgbdSimulator::applyRadialBias(cv::Mat& depth) const
{
  if (m_opts.depthRadialBias == 0)
    return;
  // The pixel grid the depth lies on: the colour camera's (registered; with
  // a lens, r of the distorted pixel, as a sensor-fixed pattern is) or the
  // depth camera's own.
  const mrpt::img::TCamera cam = m_opts.depthRegistered ? camera() : depthCamera();
  const double c = m_opts.depthRadialBias;
  for (int v = 0; v < depth.rows; ++v)
  {
    const double y = (v - cam.cy()) / cam.fy();
    auto* row = depth.ptr<float>(v);
    for (int u = 0; u < depth.cols; ++u)
    {
      const double x = (u - cam.cx()) / cam.fx();
      row[u] = static_cast<float>(row[u] * (1 + c * (x * x + y * y)));
    }
  }
}

void CRgbdSimulator::corrupt(TFrame& f, std::size_t i) const
{
  // The sensor's fixed bias first: its range limits and noise act on what
  // it reads.
  applyRadialBias(f.depth);
  CKinectNoiseModel::applyRange(f.depth, m_opts.minDepth, m_opts.maxDepth);
  if (!m_opts.noise)
    return;
  CKinectNoiseModel::TParams np;
  np.sigmaA = m_opts.depthNoiseA;
  np.sigmaB = m_opts.depthNoiseB;
  np.sigmaZ0 = m_opts.depthNoiseZ0;
  np.edgeJumpRatio = m_opts.edgeJumpRatio;
  np.rgbNoiseStd = m_opts.rgbNoiseStd;
  const CKinectNoiseModel kinect(np);
  // One stream per (seed, frame): frames can be rendered in any order.
  mrpt::random::CRandomGenerator rng(
      m_opts.seed * 2654435761u ^ (static_cast<uint32_t>(i) * 40503u + 0x9e3779b9u));
  if (m_opts.noiseModel == "disparity")
  {
    CDisparityNoiseModel(sensorDescription().depth_noise).corruptDepth(f.depth, rng);
    // The quantised depth may leave the sensor's range at its ends.
    CKinectNoiseModel::applyRange(f.depth, m_opts.minDepth, m_opts.maxDepth);
  }
  else
    kinect.corruptDepth(f.depth, rng);
  kinect.corruptColour(f.rgb, rng);
}

const detail::TDistortionMap& CRgbdSimulator::lensMap() const
{
  if (!m_impl->lens)
    m_impl->lens = detail::makeDistortionMap(
        m_impl->dist, m_opts.width, m_opts.height, m_opts.fx, m_opts.fy, m_opts.cx, m_opts.cy,
        m_opts.supersampling);
  return *m_impl->lens;
}

CRgbdSimulator::TBands CRgbdSimulator::renderColour(
    std::size_t i, double shiftX, double shiftY, cv::Mat& rgb)
{
  // A distorted colour image: a pinhole render (zoomed out if the lens sees
  // more) resampled through the lens, supersampled, then averaged down.
  const bool lens = !detail::isZero(m_impl->dist);
  const double zoom = lens ? lensMap().zoom : 1.0;
  TBands colour = renderBands(
      i, mrpt::poses::CPose3D(), m_opts.fx / zoom, m_opts.fy / zoom, m_opts.cx + shiftX,
      m_opts.cy + shiftY, 0, true, lens);
  cv::Mat rgbSS;
  if (lens)
    cv::remap(
        colour.rgbSS, rgbSS, lensMap().ssMapX, lensMap().ssMapY, cv::INTER_LINEAR,
        cv::BORDER_REPLICATE);
  else
    rgbSS = colour.rgbSS;
  if (m_opts.supersampling == 1)
    rgb = rgbSS;
  else
    cv::resize(rgbSS, rgb, cv::Size(m_opts.width, m_opts.height), 0, 0, cv::INTER_AREA);
  return colour;
}

CRgbdSimulator::TFrame CRgbdSimulator::renderFrame(std::size_t i)
{
  if (i >= m_opts.frames)
    throw std::out_of_range(
        "frame " + std::to_string(i) + " >= frames " + std::to_string(m_opts.frames));
  const unsigned ss = m_opts.supersampling;
  const unsigned W = m_opts.width, H = m_opts.height;
  if (!m_impl->fbo)
  {
    if (tGlOwner != nullptr)
      throw std::logic_error(
          "another CRgbdSimulator already renders in this thread; destroy it before rendering "
          "with a second one (MRPT keeps GL state per thread)");
    // Exact linear depth (the default LUT reads e.g. 2.9996 for 3.0 m).
    ::setenv("MRPT_FBORENDER_USE_LUT", "false", 1);
    m_impl->glScene = m_scene.makeOpenGLScene();
    try
    {
      m_impl->fbo = std::make_unique<mrpt::opengl::CFBORender>(W * ss, bandHeight() * ss);
      tGlOwner = this;
    }
    catch (const std::exception& e)
    {
      // MRPT messages span several lines; keep the first for a one-line error.
      const std::string msg = e.what();
      throw std::runtime_error(
          "cannot create the offscreen OpenGL (EGL) renderer: " + msg.substr(0, msg.find('\n')));
    }
  }

  TFrame f;
  f.index = i;
  f.timestamp = timestamp(i);
  f.depthTimestamp = f.timestamp + m_opts.depthTimeOffset;
  f.pose = groundTruthPose(i);
  // A shift of the whole colour image: its principal point moved for this
  // frame only (one stream per (seed, frame), apart from the noise's).
  double shiftX = 0, shiftY = 0;
  if (m_opts.commonShiftPx > 0)
  {
    mrpt::random::CRandomGenerator rng(
        m_opts.seed * 2246822519u ^ (static_cast<uint32_t>(i) * 3266489917u + 0x165667b1u));
    shiftX = rng.drawGaussian1D(0, m_opts.commonShiftPx);
    shiftY = rng.drawGaussian1D(0, m_opts.commonShiftPx);
  }
  const bool shifted = shiftX != 0 || shiftY != 0;
  f.colourShiftPx = {shiftX, shiftY};
  const bool lens = !detail::isZero(m_impl->dist);
  const double zoom = lens ? lensMap().zoom : 1.0;
  TBands colour = renderColour(i, shiftX, shiftY, f.rgb);
  // Unregistered depth: its own camera, rendered from where it sits on the
  // sensor, at the same row times (its rows read out with the colour's).
  // Depth stamped apart from colour, or the colour shifted: rendered on its
  // own.
  const double dt = m_opts.depthTimeOffset;
  const TBands depth =
      m_opts.depthRegistered
          ? (dt == 0 && !shifted ? std::move(colour)
                                 : renderBands(
                                       i, mrpt::poses::CPose3D(), m_opts.fx / zoom,
                                       m_opts.fy / zoom, m_opts.cx, m_opts.cy, dt, false, lens))
          : renderBands(
                i, depthPoseInColour(), m_opts.depthFx, m_opts.depthFy, m_opts.depthCx,
                m_opts.depthCy, dt);
  // Registered depth lies on the (distorted) colour grid.
  f.depth = lens && m_opts.depthRegistered
                ? detail::depthAtCentres(depth.depthSS, ss, lensMap().centres)
                : depthAtPixelCentres(depth.depthSS, ss, W, H);
  corrupt(f, i);
  return f;
}

}  // namespace roislam::sim
