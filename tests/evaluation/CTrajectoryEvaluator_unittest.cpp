// CTrajectoryEvaluator against independent computations on synthetic
// trajectories with known errors. (Agreement with the benchmark's Python
// scripts was checked by hand to ~1e-11; these tests need no Python.)
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using mrpt::poses::CPose3D;
using roislam::evaluation::CTrajectoryEvaluator;
using roislam::io::TPoseStamped;
using roislam::io::TTrajectory;

namespace
{
constexpr double kBase = 1305031100.0;  // TUM-like stamps (double spacing 2.4e-7 s)

/** Smooth random 6-DoF motion sampled every `dt` seconds for `seconds`. */
TTrajectory makeGroundTruth(double seconds, double dt, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, 1);
  TTrajectory t;
  const std::size_t count = static_cast<std::size_t>(std::lround(seconds / dt));
  double a[6], f[6];
  for (int k = 0; k < 6; ++k)
  {
    a[k] = 0.5 + 0.2 * n(rng);
    f[k] = 0.1 + 0.05 * std::abs(n(rng));
  }
  for (std::size_t k = 0; k < count; ++k)
  {
    const double s = k * dt;
    t.push_back(TPoseStamped{
        kBase + s,
        CPose3D(
            a[0] * std::sin(f[0] * s), a[1] * std::cos(f[1] * s), 0.3 * std::sin(f[2] * s),
            a[3] * std::sin(f[3] * s), 0.5 * std::sin(f[4] * s), 0.4 * std::cos(f[5] * s))});
  }
  return t;
}

const CPose3D kRigid(3.0, -2.0, 0.7, 2.5, -0.4, 2.9);  // large rotation on purpose

TTrajectory transformed(const TTrajectory& in, const CPose3D& T)
{
  TTrajectory out;
  for (const auto& p : in)
    out.push_back(TPoseStamped{p.timestamp, T + p.pose});
  return out;
}

CTrajectoryEvaluator::TOptions opts(double delta = 1, bool frames = false)
{
  CTrajectoryEvaluator::TOptions o;
  o.delta = delta;
  o.delta_unit =
      frames ? CTrajectoryEvaluator::TDeltaUnit::Frames : CTrajectoryEvaluator::TDeltaUnit::Seconds;
  return o;
}

std::string evalError(const TTrajectory& gt, const TTrajectory& est)
{
  try
  {
    CTrajectoryEvaluator().evaluate(gt, est);
  }
  catch (const std::runtime_error& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(TrajectoryEvaluator, PureRigidOffsetGivesZeroErrors)
{
  const TTrajectory gt = makeGroundTruth(20, 0.01, 1);
  const TTrajectory est = transformed(gt, kRigid);
  const auto r = CTrajectoryEvaluator().evaluate(gt, est);
  EXPECT_EQ(r.ate.pairs, gt.size());
  EXPECT_LT(r.ate.rmse, 1e-9);
  EXPECT_LT(r.ate.max, 1e-9);
  EXPECT_LT(r.rpe.trans_rmse, 1e-9);
  EXPECT_LT(r.rpe.rot_max_deg, 1e-5);  // acos near 1 amplifies rounding
  // The alignment is the inverse of the applied offset, and the aligned
  // trajectory coincides with the ground truth.
  const CPose3D back = r.ate.alignment + kRigid;
  EXPECT_LT(back.translation().norm(), 1e-9);
  EXPECT_LT((back.getRotationMatrix() - mrpt::math::CMatrixDouble33::Identity()).norm(), 1e-9);
  ASSERT_EQ(r.aligned.size(), gt.size());
  for (std::size_t k = 0; k < gt.size(); k += 97)
    EXPECT_LT((r.aligned[k].pose - gt[k].pose).translation().norm(), 1e-9);
}

TEST(TrajectoryEvaluator, AteOfKnownPerPoseOffsetsIsTheirRms)
{
  // Ground-truth positions come in equal pairs and the offsets in opposite
  // pairs (+d, -d): their sum and their cross-covariance with the positions
  // vanish, so the best alignment is exactly the applied rigid transform and
  // the ATE errors are exactly |d|.
  const TTrajectory base = makeGroundTruth(10, 0.02, 2);
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0, 0.05);
  TTrajectory gt, noisy;
  std::vector<double> expected;
  for (std::size_t k = 0; k < base.size(); ++k)
  {
    const double s = kBase + 0.01 * static_cast<double>(2 * k);
    const CPose3D& p = base[k].pose;
    gt.push_back(TPoseStamped{s, p});
    gt.push_back(TPoseStamped{s + 0.01, p});
    const double d[3] = {n(rng), n(rng), n(rng)};
    for (int sign : {+1, -1})
    {
      CPose3D q = p;
      q.x_incr(sign * d[0]);
      q.y_incr(sign * d[1]);
      q.z_incr(sign * d[2]);
      noisy.push_back(TPoseStamped{sign > 0 ? s : s + 0.01, q});
      expected.push_back(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
  }
  double sumSq = 0, sum = 0;
  for (double e : expected)
  {
    sumSq += e * e;
    sum += e;
  }
  const double n2 = static_cast<double>(expected.size());
  std::sort(expected.begin(), expected.end());
  double var = 0;
  for (double e : expected)
    var += (e - sum / n2) * (e - sum / n2);

  CTrajectoryEvaluator::TOptions o;
  o.max_difference = 0.004;  // one-to-one by stamp
  const auto r = CTrajectoryEvaluator(o).evaluate(gt, transformed(noisy, kRigid));
  EXPECT_EQ(r.ate.pairs, expected.size());
  EXPECT_NEAR(r.ate.rmse, std::sqrt(sumSq / n2), 1e-9);
  EXPECT_NEAR(r.ate.mean, sum / n2, 1e-9);
  EXPECT_NEAR(r.ate.std, std::sqrt(var / n2), 1e-9);  // population std
  EXPECT_NEAR(r.ate.min, expected.front(), 1e-9);
  EXPECT_NEAR(r.ate.max, expected.back(), 1e-9);
  const std::size_t m = expected.size() / 2;  // even count: mean of the middle two
  EXPECT_NEAR(r.ate.median, 0.5 * (expected[m - 1] + expected[m]), 1e-9);
  EXPECT_GT(r.ate.rmse, 0.05);  // the noise is really there

  // The per-pose samples (the error-over-time plot): one per pair, in stamp
  // order, each the error applied at its stamp.
  ASSERT_EQ(r.ate.samples.size(), r.ate.pairs);
  double samplesSq = 0;
  for (std::size_t k = 0; k < r.ate.samples.size(); ++k)
  {
    const auto& smp = r.ate.samples[k];
    if (k > 0)
      EXPECT_LT(r.ate.samples[k - 1].timestamp, smp.timestamp);
    EXPECT_EQ(smp.timestamp, noisy[k].timestamp);
    EXPECT_NEAR(
        smp.error,
        std::sqrt(
            std::pow(noisy[k].pose.x() - gt[k].pose.x(), 2) +
            std::pow(noisy[k].pose.y() - gt[k].pose.y(), 2) +
            std::pow(noisy[k].pose.z() - gt[k].pose.z(), 2)),
        1e-9);
    samplesSq += smp.error * smp.error;
  }
  EXPECT_NEAR(std::sqrt(samplesSq / n2), r.ate.rmse, 1e-12);
}

TEST(TrajectoryEvaluator, JitteredStampsMissingStretchAndShuffledInput)
{
  // Ground truth at 100 Hz; estimate at 30 Hz with +-4 ms jitter, a 2.5 s
  // hole, stamps shifted by 0.3 s (undone with offset) and shuffled order.
  const TTrajectory gt = makeGroundTruth(20, 0.01, 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  TTrajectory est;
  for (int k = 0; k < 570; ++k)
  {
    const double s = 0.5 + k / 30.0 + jitter(rng);
    if (s > 6.0 && s < 8.5)
      continue;
    const std::size_t g = static_cast<std::size_t>(std::lround(s / 0.01));
    // Pose of the nearest ground-truth stamp, as if estimated perfectly.
    est.push_back(TPoseStamped{gt[g].timestamp + (s - g * 0.01) + 0.3, kRigid + gt[g].pose});
  }
  const std::size_t nEst = est.size();
  std::shuffle(est.begin(), est.end(), rng);
  TTrajectory gtShuffled = gt;
  std::shuffle(gtShuffled.begin(), gtShuffled.end(), rng);

  CTrajectoryEvaluator::TOptions o;
  o.offset = -0.3;
  const auto r = CTrajectoryEvaluator(o).evaluate(gtShuffled, est);
  EXPECT_EQ(r.ate.pairs, nEst);  // every estimate associates (|jitter| < 5 ms)
  EXPECT_LT(r.ate.rmse, 1e-9);
  EXPECT_LT(r.rpe.trans_rmse, 1e-9);
  EXPECT_GT(r.rpe.pairs, nEst - 40);

  // Without the offset each estimate meets the ground truth of 0.3 s later.
  EXPECT_GT(CTrajectoryEvaluator().evaluate(gt, est).ate.rmse, 1e-3);
  // The same input sorted gives identical figures.
  std::sort(est.begin(), est.end(), [](auto& a, auto& b) { return a.timestamp < b.timestamp; });
  const auto sorted = CTrajectoryEvaluator(o).evaluate(gt, est);
  EXPECT_EQ(sorted.ate.rmse, r.ate.rmse);
  EXPECT_EQ(sorted.rpe.pairs, r.rpe.pairs);
  EXPECT_EQ(sorted.rpe.trans_rmse, r.rpe.trans_rmse);
}

TEST(TrajectoryEvaluator, RpeOfConstantTranslationalDriftPerSecond)
{
  // est(t) = gt(t) shifted by v t in the world frame: every pair 1 s apart
  // has relative error |v| * 1 s and no rotation; ATE is not zero (drift).
  const TTrajectory gt = makeGroundTruth(10, 0.05, 4);  // 200 poses
  const double v[3] = {0.03, -0.04, 0.12};              // |v| = 0.13 m/s
  TTrajectory est;
  for (const auto& p : gt)
  {
    const double s = p.timestamp - kBase;
    est.push_back(
        TPoseStamped{p.timestamp, CPose3D(v[0] * s, v[1] * s, v[2] * s, 0, 0, 0) + p.pose});
  }
  const auto r = CTrajectoryEvaluator(opts(1.0)).evaluate(gt, transformed(est, kRigid));
  // j = i + 20; pairs whose j is the last index (199) or beyond are dropped.
  EXPECT_EQ(r.rpe.pairs, 200u - 21u);
  EXPECT_NEAR(r.rpe.trans_rmse, 0.13, 1e-6);
  EXPECT_NEAR(r.rpe.trans_min, 0.13, 1e-6);
  EXPECT_NEAR(r.rpe.trans_max, 0.13, 1e-6);
  EXPECT_LT(r.rpe.rot_max_deg, 1e-5);
  EXPECT_GT(r.ate.rmse, 0.1);
  ASSERT_EQ(r.rpe.samples.size(), r.rpe.pairs);
  for (std::size_t k = 0; k < r.rpe.samples.size(); ++k)
  {
    EXPECT_EQ(r.rpe.samples[k].timestamp, gt[k].timestamp);  // the pair's first pose
    EXPECT_NEAR(r.rpe.samples[k].trans, 0.13, 1e-6);
    EXPECT_LT(r.rpe.samples[k].rot_deg, 1e-5);
  }

  // In frames: delta 10 frames = 0.5 s.
  const auto f = CTrajectoryEvaluator(opts(10, true)).evaluate(gt, est);
  EXPECT_EQ(f.rpe.pairs, 200u - 11u);
  EXPECT_NEAR(f.rpe.trans_mean, 0.065, 1e-6);
}

TEST(TrajectoryEvaluator, RpeOfConstantRotationalDriftPerSecond)
{
  // A camera that only rotates at the origin (like fr1/rpy), and an estimate
  // rotating an extra 2 deg/s about the world x axis: the error of each pair
  // 1 s apart is G_i^-1 D(1 s) G_i, a rotation of exactly 2 deg.
  const TTrajectory moving = makeGroundTruth(10, 0.05, 5);
  const double rate = 2.0 * M_PI / 180.0;
  TTrajectory gt, est;
  for (const auto& p : moving)
  {
    const CPose3D g(0, 0, 0, p.pose.yaw(), p.pose.pitch(), p.pose.roll());
    const double s = p.timestamp - kBase;
    gt.push_back(TPoseStamped{p.timestamp, g});
    est.push_back(TPoseStamped{p.timestamp, CPose3D(0, 0, 0, 0, 0, rate * s) + g});
  }
  const auto r = CTrajectoryEvaluator().evaluate(gt, est);
  EXPECT_EQ(r.rpe.pairs, 179u);
  EXPECT_NEAR(r.rpe.rot_rmse_deg, 2.0, 1e-6);
  EXPECT_NEAR(r.rpe.rot_min_deg, 2.0, 1e-6);
  EXPECT_NEAR(r.rpe.rot_max_deg, 2.0, 1e-6);
  EXPECT_LT(r.rpe.trans_max, 1e-9);
}

TEST(TrajectoryEvaluator, RpeDropsPairsWithoutNearbyGroundTruth)
{
  // Ground truth at 100 Hz with a hole (4.0 s, 6.0 s): the threshold is
  // 2 x median interval = 0.02 s, so estimates at 4.05 .. 5.95 s (indices
  // 81..119 of a 20 Hz estimate) have no ground truth; pairs (i, i+20)
  // touching them (i in 61..119) are dropped: 179 - 59 = 120 remain.
  const TTrajectory full = makeGroundTruth(10, 0.01, 6);
  TTrajectory gt;
  for (const auto& p : full)
  {
    const double s = p.timestamp - kBase;
    if (s > 4.001 && s < 5.999)
      continue;
    gt.push_back(p);
  }
  TTrajectory est;
  for (std::size_t k = 0; k < 200; ++k)
    est.push_back(full[5 * k]);
  const auto r = CTrajectoryEvaluator().evaluate(gt, transformed(est, kRigid));
  EXPECT_EQ(r.rpe.pairs, 120u);
  EXPECT_EQ(r.ate.pairs, 200u - 39u);
  EXPECT_LT(r.rpe.trans_rmse, 1e-9);
}

TEST(TrajectoryEvaluator, RepeatedStampKeepsTheLastPose)
{
  const TTrajectory gt = makeGroundTruth(5, 0.05, 8);
  TTrajectory est = gt;
  // A wrong pose with the same stamp before the right one: ignored.
  est.insert(est.begin() + 10, TPoseStamped{gt[10].timestamp, CPose3D(9, 9, 9, 0, 0, 0)});
  const auto r = CTrajectoryEvaluator().evaluate(gt, est);
  EXPECT_EQ(r.ate.pairs, gt.size());
  EXPECT_LT(r.ate.rmse, 1e-9);
  // ... but a wrong pose after it wins.
  est = gt;
  est.insert(est.begin() + 11, TPoseStamped{gt[10].timestamp, CPose3D(9, 9, 9, 0, 0, 0)});
  EXPECT_GT(CTrajectoryEvaluator().evaluate(gt, est).ate.max, 1.0);
}

TEST(TrajectoryEvaluator, BadInputGivesOneLineReasons)
{
  const TTrajectory gt = makeGroundTruth(5, 0.01, 9);
  EXPECT_EQ(evalError({}, gt), "the ground-truth trajectory is empty");
  EXPECT_EQ(evalError(gt, {}), "the estimated trajectory is empty");
  TTrajectory two(gt.begin(), gt.begin() + 2);
  EXPECT_NE(evalError(gt, two).find("only 2 estimated stamps associate"), std::string::npos);
  TTrajectory shortEst(gt.begin(), gt.begin() + 50);  // 0.5 s < delta
  EXPECT_NE(evalError(gt, shortEst).find("RPE pose pairs"), std::string::npos);
  TTrajectory far = transformed(gt, kRigid);
  for (auto& p : far)
    p.timestamp += 100;
  EXPECT_EQ(
      evalError(gt, far),
      "no estimated stamp has a ground-truth stamp within max_difference 0.02 s, offset 0 s");
}

TEST(TrajectoryEvaluator, OptionsFromIniAndValidation)
{
  mrpt::config::CConfigFileMemory cfg(
      "[TrajectoryEvaluation]\nmax_difference = 0.05\noffset=-0.25\ndelta=5\ndelta_unit=f\n");
  CTrajectoryEvaluator::TOptions o;
  o.loadFromConfigFile(cfg, "TrajectoryEvaluation");
  EXPECT_DOUBLE_EQ(o.max_difference, 0.05);
  EXPECT_DOUBLE_EQ(o.offset, -0.25);
  EXPECT_DOUBLE_EQ(o.delta, 5);
  EXPECT_EQ(o.delta_unit, CTrajectoryEvaluator::TDeltaUnit::Frames);

  // Round trip through saveToConfigFile.
  mrpt::config::CConfigFileMemory saved;
  o.saveToConfigFile(saved, "S");
  CTrajectoryEvaluator::TOptions back;
  back.loadFromConfigFile(saved, "S");
  EXPECT_DOUBLE_EQ(back.offset, -0.25);
  EXPECT_EQ(back.delta_unit, CTrajectoryEvaluator::TDeltaUnit::Frames);

  // Missing keys keep the defaults.
  CTrajectoryEvaluator::TOptions d;
  d.loadFromConfigFile(mrpt::config::CConfigFileMemory("[Other]\nx=1\n"), "TrajectoryEvaluation");
  EXPECT_DOUBLE_EQ(d.max_difference, 0.02);
  EXPECT_EQ(d.delta_unit, CTrajectoryEvaluator::TDeltaUnit::Seconds);

  auto loadError = [](const std::string& ini)
  {
    CTrajectoryEvaluator::TOptions x;
    try
    {
      x.loadFromConfigFile(mrpt::config::CConfigFileMemory(ini), "TrajectoryEvaluation");
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(
      loadError("[TrajectoryEvaluation]\nmax_difference=abc\n"),
      "[TrajectoryEvaluation] max_difference: not a number: 'abc'");
  EXPECT_EQ(
      loadError("[TrajectoryEvaluation]\nmax_difference=0\n"),
      "[TrajectoryEvaluation] max_difference: must be > 0 s, got 0");
  EXPECT_EQ(
      loadError("[TrajectoryEvaluation]\ndelta=-1\n"),
      "[TrajectoryEvaluation] delta: must be > 0, got -1");
  EXPECT_EQ(
      loadError("[TrajectoryEvaluation]\ndelta_unit=m\n"),
      "[TrajectoryEvaluation] delta_unit: must be 's' or 'f', not 'm'");
  CTrajectoryEvaluator::TOptions bad;
  bad.delta = 0;
  EXPECT_THROW(CTrajectoryEvaluator{bad}, std::invalid_argument);
}

TEST(TrajectoryEvaluator, JsonHasTheDocumentedLayout)
{
  const TTrajectory gt = makeGroundTruth(5, 0.01, 10);
  const auto r = CTrajectoryEvaluator().evaluate(gt, transformed(gt, kRigid));
  const auto j = roislam::evaluation::toJson(r);
  for (const char* k : {"rmse", "mean", "median", "std", "min", "max", "pairs", "mirrored_rmse"})
    EXPECT_TRUE(j["ate"].contains(k)) << k;
  for (const char* k :
       {"trans_rmse", "rot_rmse_deg", "trans_mean", "rot_mean_deg", "pairs", "trans_median",
        "trans_max", "rot_median_deg", "rot_max_deg"})
    EXPECT_TRUE(j["rpe"].contains(k)) << k;
  EXPECT_EQ(j["ate"]["pairs"].get<std::size_t>(), gt.size());
  EXPECT_EQ(j["rpe"]["pairs"].get<std::size_t>(), r.rpe.pairs);
  EXPECT_DOUBLE_EQ(j["ate"]["rmse"].get<double>(), r.ate.rmse);
}

TEST(TrajectoryEvaluator, AssociatesPairsJustInsideTheWindowLikeAssociatePy)
{
  // Decimal stamps 0.02 s apart whose double difference is just below 0.02
  // while t_gt + 0.02 rounds onto t_est: associate.py accepts them (its test
  // is |t_gt - t_est| < 0.02); a window bounded by the rounded sum would not.
  TTrajectory gt, est;
  for (int k = 0; k < 400 && gt.size() < 40; ++k)
  {
    const int tenThousandths = 537 * k;  // 0.0537 s steps, 4 decimals like TUM ground truth
    char a[64], x[64];
    const double ta = 1305031228.0 + tenThousandths / 10000.0;
    std::snprintf(a, sizeof(a), "%.4f", ta);
    std::snprintf(x, sizeof(x), "%.6f", ta + 0.02);
    const double ga = std::stod(a), ex = std::stod(x);
    if (!(ex == ga + 0.02 && ex - ga < 0.02))
      continue;
    const CPose3D p(std::sin(0.1 * k), std::cos(0.1 * k), 0.01 * k, 0.1 * k, 0.2, 0);
    gt.push_back(TPoseStamped{ga, p});
    est.push_back(TPoseStamped{ex, kRigid + p});
  }
  ASSERT_GE(gt.size(), 20u);
  const auto r = CTrajectoryEvaluator().evaluate(gt, est);
  EXPECT_EQ(r.ate.pairs, gt.size());
  EXPECT_LT(r.ate.rmse, 1e-9);
}

TEST(TrajectoryEvaluator, AMirroredEstimateIsRecognised)
{
  // The estimate a y-up ground truth (ICL-NUIM) gets from a camera given
  // fy > 0: every pose P as S P S, S = diag(1, -1, 1), then placed anywhere.
  // A helix: chiral, so no rotation maps it onto its mirror image.
  TTrajectory gt;
  for (int k = 0; k < 400; ++k)
  {
    const double t = k * 0.03;
    gt.push_back(TPoseStamped{
        kBase + t, CPose3D(std::cos(t), std::sin(t), 0.1 * t, 0.2 * t, 0.1 * std::sin(t), 0.3)});
  }
  TTrajectory mirrored;
  for (const auto& p : gt)
  {
    auto R = p.pose.getRotationMatrix();
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        if ((i == 1) != (k == 1))
          R(i, k) = -R(i, k);
    mrpt::math::CVectorFixedDouble<3> t;
    t[0] = p.pose.x();
    t[1] = -p.pose.y();
    t[2] = p.pose.z();
    mirrored.push_back(TPoseStamped{p.timestamp, kRigid + CPose3D(R, t)});
  }
  const auto bad = CTrajectoryEvaluator().evaluate(gt, mirrored);
  EXPECT_GT(bad.ate.rmse, 0.05);
  EXPECT_LT(bad.ate.mirrored_rmse, 1e-9);
  EXPECT_NE(roislam::evaluation::mirrorWarning(bad.ate).find("fy < 0"), std::string::npos);

  const auto good = CTrajectoryEvaluator().evaluate(gt, transformed(gt, kRigid));
  EXPECT_GT(good.ate.mirrored_rmse, 0.05);
  EXPECT_TRUE(roislam::evaluation::mirrorWarning(good.ate).empty());
}
