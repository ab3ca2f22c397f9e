// Agreement with the TUM RGB-D benchmark's own scripts on a fixed input.
//
// data/script_agreement_{gt,est}.txt: synthetic ground truth (TUM layout, 4
// decimals, ~100 Hz, a 0.5 s hole) and an estimate (6 decimals, ~30 Hz with
// jitter, rigidly moved, noisy, drifting, a 0.4 s hole, shuffled lines, mixed
// comma/tab/space separators, sign-flipped quaternions, one repeated stamp
// whose later line wins, some stamps exactly 0.02 s after a ground-truth one).
// The expected figures were produced once by running associate.py,
// evaluate_ate.py's align() and evaluate_rpe.py's evaluate_trajectory()
// (--fixed_delta, max_pairs 0; python3 port of the TUM scripts, numpy 1.24)
// on these files and printing full precision. No Python is needed here.
#include <gtest/gtest.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/testing/TestData.h>

using roislam::evaluation::CTrajectoryEvaluator;

namespace
{
struct TExpected
{
  double rmse, mean, median, std, min, max;
  std::size_t pairs;
  double trmse, tmean, tmedian, tstd, tmin, tmax;
  double rrmse, rmean, rmedian, rstd, rmin, rmax;
  std::size_t rpairs;
};

void expectAgreement(const roislam::evaluation::TEvaluationResult& r, const TExpected& e)
{
  constexpr double m = 1e-9, deg = 1e-8;
  EXPECT_EQ(r.ate.pairs, e.pairs);
  EXPECT_NEAR(r.ate.rmse, e.rmse, m);
  EXPECT_NEAR(r.ate.mean, e.mean, m);
  EXPECT_NEAR(r.ate.median, e.median, m);
  EXPECT_NEAR(r.ate.std, e.std, m);
  EXPECT_NEAR(r.ate.min, e.min, m);
  EXPECT_NEAR(r.ate.max, e.max, m);
  EXPECT_EQ(r.rpe.pairs, e.rpairs);
  EXPECT_NEAR(r.rpe.trans_rmse, e.trmse, m);
  EXPECT_NEAR(r.rpe.trans_mean, e.tmean, m);
  EXPECT_NEAR(r.rpe.trans_median, e.tmedian, m);
  EXPECT_NEAR(r.rpe.trans_std, e.tstd, m);
  EXPECT_NEAR(r.rpe.trans_min, e.tmin, m);
  EXPECT_NEAR(r.rpe.trans_max, e.tmax, m);
  EXPECT_NEAR(r.rpe.rot_rmse_deg, e.rrmse, deg);
  EXPECT_NEAR(r.rpe.rot_mean_deg, e.rmean, deg);
  EXPECT_NEAR(r.rpe.rot_median_deg, e.rmedian, deg);
  EXPECT_NEAR(r.rpe.rot_std_deg, e.rstd, deg);
  EXPECT_NEAR(r.rpe.rot_min_deg, e.rmin, deg);
  EXPECT_NEAR(r.rpe.rot_max_deg, e.rmax, deg);
}

std::string dataFile(const std::string& name)
{
  return roislam::testing::sourceDir() + "/tests/evaluation/data/" + name;
}
}  // namespace

TEST(ScriptAgreement, DefaultOptions)
{
  // evaluate_ate.py --max_difference 0.02; evaluate_rpe.py --fixed_delta --delta 1 --delta_unit s
  const auto gt = roislam::io::loadTumTrajectory(dataFile("script_agreement_gt.txt"));
  const auto est = roislam::io::loadTumTrajectory(dataFile("script_agreement_est.txt"));
  expectAgreement(
      CTrajectoryEvaluator().evaluate(gt, est), {0.056432956444634697,
                                                 0.0390733008797967,
                                                 0.03594860816058743,
                                                 0.04071800254726298,
                                                 0.007403874295319871,
                                                 0.4956483378648428,
                                                 150,
                                                 0.0795140954296986,
                                                 0.04185193498876869,
                                                 0.03223068245500233,
                                                 0.06760848252770577,
                                                 0.007198939324906616,
                                                 0.5231024489181884,
                                                 3.0192834978722467,
                                                 2.7426371946290065,
                                                 2.571763486688051,
                                                 1.2625426959755495,
                                                 0.750397830637667,
                                                 6.069212210699146,
                                                 105});
}

TEST(ScriptAgreement, OffsetAndFrameDelta)
{
  // --max_difference 0.01 --offset 0.005; --fixed_delta --delta 5 --delta_unit f --offset 0.005
  CTrajectoryEvaluator::TOptions o;
  o.max_difference = 0.01;
  o.offset = 0.005;
  o.delta = 5;
  o.delta_unit = CTrajectoryEvaluator::TDeltaUnit::Frames;
  const auto gt = roislam::io::loadTumTrajectory(dataFile("script_agreement_gt.txt"));
  const auto est = roislam::io::loadTumTrajectory(dataFile("script_agreement_est.txt"));
  expectAgreement(
      CTrajectoryEvaluator(o).evaluate(gt, est), {0.056158989817717615,
                                                  0.03869914198752547,
                                                  0.03503874435980093,
                                                  0.04069654219679913,
                                                  0.008378958782919074,
                                                  0.4949130767851023,
                                                  149,
                                                  0.06703817678463157,
                                                  0.029982279671237858,
                                                  0.021445394530296917,
                                                  0.059959820315968186,
                                                  0.0030982688580850656,
                                                  0.5204406925162262,
                                                  2.677288912069194,
                                                  2.4641853616110225,
                                                  2.3704439898686394,
                                                  1.0467408572854122,
                                                  0.27813742069936803,
                                                  5.187454021748655,
                                                  138});
}
