/* roislam-geometry-bench: libs/geometry against the library alternatives.
 *
 * 1. The closed-form rigid alignment (geometry::alignRigid)
 * (Eigen::umeyama without scale, plus its degeneracy test) against the raw
 * library candidates, Eigen::umeyama and mrpt::tfest::se3_l2 (Horn's
 * quaternion method), and against the hand-written SVD loop the RANSAC had
 * (svd_loop), on the uses it serves:
 *  - Align/<method>/3: one minimal RANSAC sample (3 pairs out of 300, as
 *    CRigidTransformRansac draws them);
 *  - Align/<method>/<n>, n = 100, 250, 500: a least-squares refit on the n
 *    inliers out of 500 pairs (CRigidTransformRansac's final refits) or an
 *    ATE alignment of n associated poses (CTrajectoryEvaluator).
 * Each method is given what its caller holds (Eigen points and an index list)
 * and gathers what it needs, as it would in the caller.
 * Counters: rot_err_urad / trans_err_um = mean error against the true motion
 * (points 1-4 m ahead, 5 mm Gaussian noise, 64 random problems), and
 * rot_vs_ours_urad = mean rotation difference from alignRigid's answer.
 * Figures: libs/geometry/include/roislam/geometry/RigidAlignment.h.
 *
 * 2. SO(3) exp and log (geometry::expSO3 / logSO3, Eigen::AngleAxisd) against
 *    mrpt::poses::Lie::SO<3>: So3Exp|So3Log/<method>/<k>, rotation vectors of
 *    1e-k rad (k = 9, 6, 3, 0) about 1000 random axes. Counters: exp_err =
 *    largest entry error against Rodrigues' formula in long double, log_rel_err
 *    = largest |log(R) - w| / |w| for R that formula's matrix.
 *    Figures: libs/geometry/include/roislam/geometry/Rotation.h.
 *
 * 3. Keypoint lifting (geometry::liftPixels + TPinhole::backProject) against
 *    cv::rgbd::depthTo3dSparse: Lift/<method> on 10 frames of the shared
 *    fr1/rpy sequence (every 25th; 600 ORB keypoints each; fr1 intrinsics
 *    and distortion). depthTo3dSparse gets the keypoints' pixels and keeps
 *    the points within the depth range. Counters: points per frame, and for
 *    keypoints both lift: mean / max 3-D distance from liftPixels' point (mm)
 *    and the share whose depth reading differs (it truncates the pixel).
 *    Skipped without the shared data.
 *    Figures: libs/geometry/include/roislam/geometry/KeypointLifting.h.
 *
 * Run: build/tests/benchmark/roislam-geometry-bench --benchmark_repetitions=3
 */
#include <benchmark/benchmark.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3DQuat.h>
#include <mrpt/poses/Lie/SO.h>
#include <mrpt/tfest/se3.h>
#include <roislam/geometry/KeypointLifting.h>
#include <roislam/geometry/RigidAlignment.h>
#include <roislam/geometry/Rotation.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/rgbd.hpp>
#include <random>
#include <vector>

namespace
{
using roislam::geometry::TRigid;

struct TProblem
{
  std::vector<Eigen::Vector3d> a, b;  // a ~= truth * b
  std::vector<std::size_t> idx;       // the pairs to align
  TRigid truth;
};

std::vector<TProblem> makeProblems(std::size_t pairs, std::size_t used)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> noise(0, 0.005);
  std::vector<TProblem> out(64);
  for (auto& p : out)
  {
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    p.truth.R = Eigen::AngleAxisd(0.3 * u(rng), axis).toRotationMatrix();
    p.truth.t = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.2;
    for (std::size_t i = 0; i < pairs; ++i)
    {
      const Eigen::Vector3d b(1.5 * u(rng), 1.0 * u(rng), 2.5 + 1.5 * u(rng));
      p.b.push_back(b);
      p.a.push_back(p.truth * b + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    }
    std::vector<std::size_t> all(pairs);
    for (std::size_t i = 0; i < pairs; ++i)
      all[i] = i;
    std::shuffle(all.begin(), all.end(), rng);
    p.idx.assign(all.begin(), all.begin() + static_cast<long>(used));
  }
  return out;
}

double angle(const Eigen::Matrix3d& R)
{
  return Eigen::AngleAxisd(R).angle();
}

TRigid ours(const TProblem& p)
{
  if (p.idx.size() == 3)
  {
    // As CRigidTransformRansac's minimal samples.
    Eigen::Matrix3d A, B;
    for (Eigen::Index k = 0; k < 3; ++k)
    {
      A.col(k) = p.a[p.idx[static_cast<std::size_t>(k)]];
      B.col(k) = p.b[p.idx[static_cast<std::size_t>(k)]];
    }
    return roislam::geometry::alignRigid(A, B);
  }
  const auto [A, B] = roislam::geometry::gatherPairs(p.a, p.b, p.idx);
  return roislam::geometry::alignRigid(A, B);
}

// The hand-written SVD loop the RANSAC had before (for the record).
TRigid svdLoop(const TProblem& p)
{
  const std::size_t n = p.idx.size();
  Eigen::Vector3d ca = Eigen::Vector3d::Zero(), cb = Eigen::Vector3d::Zero();
  for (auto i : p.idx)
  {
    ca += p.a[i];
    cb += p.b[i];
  }
  ca /= static_cast<double>(n);
  cb /= static_cast<double>(n);
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (auto i : p.idx)
    S += (p.a[i] - ca) * (p.b[i] - cb).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0)
    D(2, 2) = -1;
  TRigid T;
  T.R = svd.matrixU() * D * svd.matrixV().transpose();
  T.t = ca - T.R * cb;
  return T;
}

TRigid umeyama(const TProblem& p)
{
  const auto n = static_cast<Eigen::Index>(p.idx.size());
  Eigen::Matrix4d M;
  if (n == 3)
  {
    Eigen::Matrix3d src, dst;
    for (Eigen::Index k = 0; k < 3; ++k)
    {
      src.col(k) = p.b[p.idx[k]];
      dst.col(k) = p.a[p.idx[k]];
    }
    M = Eigen::umeyama(src, dst, false);
  }
  else
  {
    Eigen::Matrix3Xd src(3, n), dst(3, n);
    for (Eigen::Index k = 0; k < n; ++k)
    {
      src.col(k) = p.b[p.idx[k]];
      dst.col(k) = p.a[p.idx[k]];
    }
    M = Eigen::umeyama(src, dst, false);
  }
  TRigid T;
  T.R = M.topLeftCorner<3, 3>();
  T.t = M.topRightCorner<3, 1>();
  return T;
}

TRigid horn(const TProblem& p)
{
  std::vector<mrpt::math::TPoint3D> sa, sb;
  sa.reserve(p.idx.size());
  sb.reserve(p.idx.size());
  for (auto i : p.idx)
  {
    sa.emplace_back(p.a[i].x(), p.a[i].y(), p.a[i].z());
    sb.emplace_back(p.b[i].x(), p.b[i].y(), p.b[i].z());
  }
  mrpt::poses::CPose3DQuat q;
  double scale = 1;
  mrpt::tfest::se3_l2(sa, sb, q, scale, true);
  const mrpt::poses::CPose3D pose(q);
  return TRigid::fromPose(pose);
}

template <TRigid (*Method)(const TProblem&)>
void Align(benchmark::State& state)
{
  const auto used = static_cast<std::size_t>(state.range(0));
  const auto problems = makeProblems(used == 3 ? 300 : 500, used);
  std::size_t i = 0;
  for (auto _ : state)
  {
    const TRigid T = Method(problems[i++ % problems.size()]);
    benchmark::DoNotOptimize(T.R.data());
  }
  double rotErr = 0, transErr = 0, vsOurs = 0;
  for (const auto& p : problems)
  {
    const TRigid T = Method(p), O = ours(p);
    rotErr += angle(T.R * p.truth.R.transpose());
    transErr += (T.t - p.truth.t).norm();
    vsOurs += angle(T.R * O.R.transpose());
  }
  const double n = static_cast<double>(problems.size());
  state.counters["rot_err_urad"] = 1e6 * rotErr / n;
  state.counters["trans_err_um"] = 1e6 * transErr / n;
  state.counters["rot_vs_ours_urad"] = 1e6 * vsOurs / n;
}
// The degeneracy test the RANSAC adds to each minimal sample and refit.
void Collinear(benchmark::State& state)
{
  const auto used = static_cast<std::size_t>(state.range(0));
  const auto problems = makeProblems(used == 3 ? 300 : 500, used);
  std::vector<Eigen::Matrix3Xd> sets;
  for (const auto& p : problems)
    sets.push_back(roislam::geometry::gatherPairs(p.a, p.b, p.idx).second);
  std::size_t i = 0;
  for (auto _ : state)
  {
    const auto& B = sets[i++ % sets.size()];
    bool c = false;
    if (used == 3)
    {
      const Eigen::Matrix3d B3 = B;
      c = roislam::geometry::collinear(B3);
    }
    else
      c = roislam::geometry::collinear(B);
    benchmark::DoNotOptimize(c);
  }
}
// ---- SO(3) ----
Eigen::Matrix3d rodriguesLongDouble(const Eigen::Vector3d& w)
{
  using L = long double;
  const L x = w.x(), y = w.y(), z = w.z();
  const L a = std::sqrt(x * x + y * y + z * z);
  const L s = std::sin(a) / a, h = std::sin(a / 2), c = 2 * h * h / (a * a);  // (1 - cos a) / a^2
  const L W[3][3] = {{0, -z, y}, {z, 0, -x}, {-y, x, 0}};
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
    {
      L w2 = 0;
      for (int k = 0; k < 3; ++k)
        w2 += W[i][k] * W[k][j];
      R(i, j) = static_cast<double>((i == j ? 1 : 0) + s * W[i][j] + c * w2);
    }
  return R;
}

std::vector<Eigen::Vector3d> rotationVectors(int k)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Vector3d> out(1000);
  for (auto& w : out)
    w = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized() * std::pow(10.0, -k);
  return out;
}

Eigen::Matrix3d expEigen(const Eigen::Vector3d& w)
{
  return roislam::geometry::expSO3(w);
}
Eigen::Matrix3d expMrpt(const Eigen::Vector3d& w)
{
  mrpt::math::CVectorFixedDouble<3> v;
  v[0] = w.x();
  v[1] = w.y();
  v[2] = w.z();
  const mrpt::math::CMatrixDouble33 R = mrpt::poses::Lie::SO<3>::exp(v);
  return R.asEigen();
}
Eigen::Vector3d logEigen(const Eigen::Matrix3d& R)
{
  return roislam::geometry::logSO3(R);
}
Eigen::Vector3d logMrpt(const Eigen::Matrix3d& R)
{
  const auto v = mrpt::poses::Lie::SO<3>::log(mrpt::math::CMatrixDouble33(R));
  return {v[0], v[1], v[2]};
}

template <Eigen::Matrix3d (*Exp)(const Eigen::Vector3d&)>
void So3Exp(benchmark::State& state)
{
  const auto ws = rotationVectors(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state)
  {
    const Eigen::Matrix3d R = Exp(ws[i++ % ws.size()]);
    benchmark::DoNotOptimize(R.data());
  }
  double err = 0;
  for (const auto& w : ws)
    err = std::max(err, (Exp(w) - rodriguesLongDouble(w)).cwiseAbs().maxCoeff());
  state.counters["exp_err"] = err;
}

template <Eigen::Vector3d (*Log)(const Eigen::Matrix3d&)>
void So3Log(benchmark::State& state)
{
  const auto ws = rotationVectors(static_cast<int>(state.range(0)));
  std::vector<Eigen::Matrix3d> Rs;
  for (const auto& w : ws)
    Rs.push_back(rodriguesLongDouble(w));
  std::size_t i = 0;
  for (auto _ : state)
  {
    const Eigen::Vector3d w = Log(Rs[i++ % Rs.size()]);
    benchmark::DoNotOptimize(w.data());
  }
  double err = 0;
  for (std::size_t k = 0; k < ws.size(); ++k)
    err = std::max(err, (Log(Rs[k]) - ws[k]).norm() / ws[k].norm());
  state.counters["log_rel_err"] = err;
}
// ---- Keypoint lifting ----
struct TLiftData
{
  std::vector<cv::Mat> depth;                    // CV_32FC1 metres
  std::vector<std::vector<cv::Point2f>> pixels;  // ORB keypoints
};

const TLiftData& liftData()
{
  static const TLiftData data = []
  {
    namespace fs = std::filesystem;
    TLiftData d;
    const fs::path seq =
        fs::path(ROISLAM_SHARED_DATA_DIR) / "tum" / "rgbd_dataset_freiburg1_rpy_first250";
    std::vector<fs::path> rgb, depth;
    std::error_code ec;
    for (const auto& [dir, out] : {std::pair{"rgb", &rgb}, std::pair{"depth", &depth}})
      for (const auto& e : fs::directory_iterator(seq / dir, ec))
        out->push_back(e.path());
    std::sort(rgb.begin(), rgb.end());
    std::sort(depth.begin(), depth.end());
    auto orb = cv::ORB::create(600);
    for (std::size_t i = 0; i < rgb.size() && i < depth.size(); i += 25)
    {
      const cv::Mat grey = cv::imread(rgb[i].string(), cv::IMREAD_GRAYSCALE);
      const cv::Mat raw = cv::imread(depth[i].string(), cv::IMREAD_UNCHANGED);
      if (grey.empty() || raw.type() != CV_16UC1)
        continue;
      cv::Mat z;
      raw.convertTo(z, CV_32F, 1.0 / 5000);
      std::vector<cv::KeyPoint> kps;
      orb->detect(grey, kps);
      std::vector<cv::Point2f> px;
      for (const auto& k : kps)
        px.push_back(k.pt);
      d.depth.push_back(z);
      d.pixels.push_back(px);
    }
    return d;
  }();
  return data;
}

// fr1 colour intrinsics and distortion (the shared data's README).
const roislam::geometry::TPinhole kFr1{517.306408, 516.469215, 318.643040, 255.313989};
const cv::Matx33d kFr1K(kFr1.fx, 0, kFr1.cx, 0, kFr1.fy, kFr1.cy, 0, 0, 1);
const cv::Vec<double, 5> kFr1Dist(0.262383, -0.953104, -0.005358, 0.002628, 1.163314);

/** Per keypoint: its point, NaN where it has none. */
std::vector<Eigen::Vector3d> liftOurs(const cv::Mat& depth, const std::vector<cv::Point2f>& px)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Eigen::Vector3d> out(px.size(), Eigen::Vector3d::Constant(nan));
  const auto l =
      roislam::geometry::liftPixels(px, depth, kFr1K, kFr1Dist, roislam::geometry::TDepthRule());
  for (int i : l.valid)
    out[static_cast<std::size_t>(i)] = kFr1.backProject(
        l.undistorted[static_cast<std::size_t>(i)], l.z[static_cast<std::size_t>(i)]);
  return out;
}

std::vector<Eigen::Vector3d> liftSparse(const cv::Mat& depth, const std::vector<cv::Point2f>& px)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Eigen::Vector3d> out(px.size(), Eigen::Vector3d::Constant(nan));
  cv::Mat p3;
  cv::rgbd::depthTo3dSparse(depth, cv::Mat(kFr1K), px, p3);
  const roislam::geometry::TDepthRule rule;
  for (std::size_t i = 0; i < px.size(); ++i)
  {
    const cv::Vec3f& X = p3.at<cv::Vec3f>(static_cast<int>(i));
    if (X[2] >= rule.min_depth_m && X[2] <= rule.max_depth_m)
      out[i] = Eigen::Vector3d(X[0], X[1], X[2]);
  }
  return out;
}

template <std::vector<Eigen::Vector3d> (*Lifter)(const cv::Mat&, const std::vector<cv::Point2f>&)>
void Lift(benchmark::State& state)
{
  const TLiftData& d = liftData();
  if (d.depth.empty())
  {
    state.SkipWithError("no shared fr1/rpy data (ROISLAM_SHARED_DATA_DIR)");
    return;
  }
  std::size_t i = 0;
  for (auto _ : state)
  {
    const auto k = i++ % d.depth.size();
    const auto pts = Lifter(d.depth[k], d.pixels[k]);
    benchmark::DoNotOptimize(pts.data());
  }
  double lifted = 0, both = 0, sum = 0, worst = 0, depthDiffers = 0;
  for (std::size_t k = 0; k < d.depth.size(); ++k)
  {
    const auto mine = liftOurs(d.depth[k], d.pixels[k]), theirs = Lifter(d.depth[k], d.pixels[k]);
    for (std::size_t j = 0; j < mine.size(); ++j)
    {
      lifted += std::isfinite(theirs[j].z()) ? 1 : 0;
      if (!std::isfinite(mine[j].z()) || !std::isfinite(theirs[j].z()))
        continue;
      const double e = (mine[j] - theirs[j]).norm();
      both += 1;
      sum += e;
      worst = std::max(worst, e);
      depthDiffers += std::abs(mine[j].z() - theirs[j].z()) > 1e-6 ? 1 : 0;
    }
  }
  state.counters["points_per_frame"] = lifted / static_cast<double>(d.depth.size());
  state.counters["mean_diff_mm"] = both > 0 ? 1e3 * sum / both : 0;
  state.counters["max_diff_mm"] = 1e3 * worst;
  state.counters["depth_differs"] = both > 0 ? depthDiffers / both : 0;
}
}  // namespace

BENCHMARK_TEMPLATE(Lift, liftOurs)->Name("Lift/ours");
BENCHMARK_TEMPLATE(Lift, liftSparse)->Name("Lift/depthTo3dSparse");
BENCHMARK_TEMPLATE(So3Exp, expEigen)->Name("So3Exp/angleaxis")->Arg(9)->Arg(6)->Arg(3)->Arg(0);
BENCHMARK_TEMPLATE(So3Exp, expMrpt)->Name("So3Exp/mrpt_lie")->Arg(9)->Arg(6)->Arg(3)->Arg(0);
BENCHMARK_TEMPLATE(So3Log, logEigen)->Name("So3Log/angleaxis")->Arg(9)->Arg(6)->Arg(3)->Arg(0);
BENCHMARK_TEMPLATE(So3Log, logMrpt)->Name("So3Log/mrpt_lie")->Arg(9)->Arg(6)->Arg(3)->Arg(0);
BENCHMARK(Collinear)->Arg(3)->Arg(250);
BENCHMARK_TEMPLATE(Align, ours)->Name("Align/ours")->Arg(3)->Arg(100)->Arg(250)->Arg(500);
BENCHMARK_TEMPLATE(Align, svdLoop)->Name("Align/svd_loop")->Arg(3)->Arg(100)->Arg(250)->Arg(500);
BENCHMARK_TEMPLATE(Align, umeyama)->Name("Align/umeyama")->Arg(3)->Arg(100)->Arg(250)->Arg(500);
BENCHMARK_TEMPLATE(Align, horn)->Name("Align/se3_l2")->Arg(3)->Arg(100)->Arg(250)->Arg(500);

BENCHMARK_MAIN();
