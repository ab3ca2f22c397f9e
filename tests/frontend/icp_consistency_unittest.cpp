// How far depth ICP is trusted beside the features (libs/frontend/src/
// IcpConsistency.h): the scale of ICP's covariance recovered from simulated
// disagreements whose true covariance is known, its bounds, the information
// share, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "IcpConsistency.h"

using roislam::frontend::detail::CIcpConsistency;
using roislam::frontend::detail::Matrix6d;
using roislam::frontend::detail::Vector6d;

namespace
{
/** A random symmetric positive-definite covariance, eigenvalues spread over
 *  two decades around `level` (poses are better known in some directions). */
Matrix6d randomCovariance(std::mt19937& rng, double level)
{
  std::normal_distribution<double> n(0, 1);
  Matrix6d A;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      A(r, c) = n(rng);
  const Eigen::HouseholderQR<Matrix6d> qr(A);
  const Matrix6d Q = qr.householderQ();
  Vector6d e;
  for (int i = 0; i < 6; ++i)
    e[i] = level * std::pow(10.0, -1.0 + 2.0 * i / 5.0);
  return Q * e.asDiagonal() * Q.transpose();
}

/** A draw from N(0, C). */
Vector6d draw(std::mt19937& rng, const Matrix6d& C)
{
  std::normal_distribution<double> n(0, 1);
  Vector6d z;
  for (int i = 0; i < 6; ++i)
    z[i] = n(rng);
  const Eigen::LLT<Matrix6d> llt(C);
  return llt.matrixL() * z;
}

/** The scale after `samples` disagreements drawn with ICP's covariance
 *  truly `trueScale` times the claimed one. */
std::optional<double> scaleFor(
    double trueScale, int samples, std::size_t window, unsigned seed, double minScale = 1.0,
    double icpLevel = 1e-7)
{
  std::mt19937 rng(seed);
  CIcpConsistency c(window, 10, minScale);
  for (int i = 0; i < samples; ++i)
  {
    const Matrix6d Sf = randomCovariance(rng, 1e-6);
    const Matrix6d Si = randomCovariance(rng, icpLevel);
    c.add(draw(rng, Sf + trueScale * Si), Sf, Si);
  }
  return c.scale();
}
}  // namespace

TEST(IcpConsistency, HonestIcpKeepsItsModelledInformation)
{
  // Disagreements as claimed: no inflation (the scale is never below 1).
  const auto k = scaleFor(1.0, 400, 400, 1);
  ASSERT_TRUE(k.has_value());
  EXPECT_GE(*k, 1.0);
  EXPECT_LT(*k, 1.5);
}

TEST(IcpConsistency, RecoversHowFarIcpIsOverconfident)
{
  for (const double truth : {10.0, 100.0, 1000.0})
  {
    SCOPED_TRACE(truth);
    const auto k = scaleFor(truth, 400, 400, 2);
    ASSERT_TRUE(k.has_value());
    EXPECT_GT(*k, truth / 2);
    EXPECT_LT(*k, truth * 2);
  }
  // A short window (the front end's 30) is noisier but of the same order.
  const auto k = scaleFor(100.0, 30, 30, 3);
  ASSERT_TRUE(k.has_value());
  EXPECT_GT(*k, 25.0);
  EXPECT_LT(*k, 400.0);
}

TEST(IcpConsistency, NoScaleBeforeEnoughComparisonsAndInfinityBeyondAnyScale)
{
  std::mt19937 rng(4);
  CIcpConsistency c(30, 10);
  const Matrix6d S = 1e-12 * Matrix6d::Identity();
  for (int i = 0; i < 9; ++i)
    c.add(draw(rng, 1e-2 * Matrix6d::Identity()), S, S);
  EXPECT_FALSE(c.scale().has_value());
  c.add(draw(rng, 1e-2 * Matrix6d::Identity()), S, S);
  ASSERT_TRUE(c.scale().has_value());
  // 10 cm disagreements against a claimed micrometre: no scale up to 1e6.
  EXPECT_TRUE(std::isinf(*c.scale()));
  c.reset();
  EXPECT_EQ(c.size(), 0u);
  EXPECT_FALSE(c.scale().has_value());
}

TEST(IcpConsistency, ShareIsIcpInformationRelativeToTheFeatures)
{
  CIcpConsistency c(30, 1);
  // Features 4x as uncertain (in variance) as ICP claims to be: ICP holds
  // four times their information.
  c.add(Vector6d::Zero(), 4e-6 * Matrix6d::Identity(), 1e-6 * Matrix6d::Identity());
  EXPECT_NEAR(c.medianShare(), 4.0, 1e-9);
  ASSERT_TRUE(c.scale().has_value());
  EXPECT_DOUBLE_EQ(*c.scale(), 1.0);
}

TEST(IcpConsistency, WindowForgetsAndBadInputIsIgnored)
{
  std::mt19937 rng(5);
  CIcpConsistency c(20, 10);
  const Matrix6d Sf = 1e-6 * Matrix6d::Identity(), Si = 1e-8 * Matrix6d::Identity();
  // A biased stretch, then an honest one: the window holds only the latter.
  for (int i = 0; i < 20; ++i)
    c.add(draw(rng, Sf + 1e4 * Si), Sf, Si);
  EXPECT_GT(*c.scale(), 20.0);
  for (int i = 0; i < 20; ++i)
    c.add(draw(rng, Sf + Si), Sf, Si);
  EXPECT_LT(*c.scale(), 3.0);
  const std::size_t n = c.size();
  Vector6d nan = Vector6d::Zero();
  nan[2] = std::nan("");
  c.add(nan, Sf, Si);
  EXPECT_EQ(c.size(), n);
  EXPECT_THROW(CIcpConsistency(0, 0), std::invalid_argument);
  EXPECT_THROW(CIcpConsistency(5, 10), std::invalid_argument);
}

TEST(IcpConsistency, RunsOnAShareOfThePairsMeasureTheSameScale)
{
  // ICP's error as modelled: a bias (k - 1) Si that fewer pairs do not
  // change plus noise Si / q. Runs on all the pairs and on a quarter of them
  // (claiming Si / q), interleaved, give back the k of all the pairs; a
  // quarter-share run's own claim is scaled by q (k - 1) + 1.
  for (const double truth : {1.0, 12.0, 60.0})
  {
    SCOPED_TRACE(truth);
    std::mt19937 rng(6);
    CIcpConsistency c(400, 10);
    for (int i = 0; i < 400; ++i)
    {
      const Matrix6d Sf = randomCovariance(rng, 1e-6);
      const Matrix6d Si = randomCovariance(rng, 1e-7);
      const double q = i % 2 ? 0.25 : 1.0;
      c.add(draw(rng, Sf + (truth - 1) * Si + Si / q), Sf, Si / q, q);
    }
    ASSERT_TRUE(c.scale().has_value());
    EXPECT_GE(*c.scale(), std::max(1.0, truth / 1.5));
    EXPECT_LT(*c.scale(), truth * 1.5);
    EXPECT_NEAR(*c.scaleFor(0.25), 0.25 * (*c.scale() - 1) + 1, 1e-12);
    EXPECT_DOUBLE_EQ(*c.scaleFor(1.0), *c.scale());
  }
  // Shares count the information all the pairs would give.
  CIcpConsistency c(30, 1);
  c.add(Vector6d::Zero(), 4e-6 * Matrix6d::Identity(), 4e-6 * Matrix6d::Identity(), 0.25);
  EXPECT_NEAR(c.medianShare(), 4.0, 1e-9);
  EXPECT_THROW(
      c.add(Vector6d::Zero(), Matrix6d::Identity(), Matrix6d::Identity(), 0),
      std::invalid_argument);
  EXPECT_THROW(
      c.add(Vector6d::Zero(), Matrix6d::Identity(), Matrix6d::Identity(), 1.5),
      std::invalid_argument);
}

TEST(IcpConsistency, AQuarterOfThePairsKeepsTheInformationABiasLeaves)
{
  // No scale yet, or honest ICP (noise only): a quarter of the pairs keeps a
  // quarter of the information. A bias k = 12 (a Kinect's ICP reads 10-140)
  // keeps 12 / 15 = 0.8 of it, k = 100 nearly all.
  CIcpConsistency none(30, 10);
  EXPECT_DOUBLE_EQ(none.informationKept(0.25), 0.25);
  auto withScale = [](double k)
  {
    CIcpConsistency c(30, 1);
    // One comparison whose chi-square under Sf + k Si is chi-square's
    // median: d along one axis, Sf = 0, Si = I.
    Vector6d d = Vector6d::Zero();
    d[0] = std::sqrt(CIcpConsistency::kChi2Median6 * k);
    c.add(d, 1e-12 * Matrix6d::Identity(), Matrix6d::Identity());
    return c;
  };
  for (const double k : {1.0, 12.0, 100.0})
  {
    SCOPED_TRACE(k);
    const CIcpConsistency c = withScale(k);
    ASSERT_TRUE(c.scale().has_value());
    EXPECT_NEAR(*c.scale(), k, 0.01 * k);
    EXPECT_NEAR(c.informationKept(0.25), *c.scale() / (*c.scale() + 3), 1e-12);
    EXPECT_DOUBLE_EQ(c.informationKept(1.0), 1.0);
  }
  EXPECT_NEAR(withScale(12.0).informationKept(0.25), 0.8, 0.01);
}

TEST(IcpConsistency, BelowItsModelDownToTheLeastScale)
{
  // ICP better than it claims (rendered depth: every pair nearly
  // independent): with a least scale below 1 the scale follows it down,
  // where ICP claims as much as the features (below, the features' own
  // error hides ICP's and the scale is poorly determined)...
  for (const double truth : {0.5, 0.2, 0.08})
  {
    SCOPED_TRACE(truth);
    const auto k = scaleFor(truth, 400, 400, 7, 0.04, 1e-6 / truth);
    ASSERT_TRUE(k.has_value());
    EXPECT_GT(*k, truth / 1.5);
    EXPECT_LT(*k, truth * 1.5);
  }
  // ... to the least scale and no further, and not at all with the default.
  const auto floor = scaleFor(0.001, 400, 400, 8, 0.04, 1e-5);
  ASSERT_TRUE(floor.has_value());
  EXPECT_DOUBLE_EQ(*floor, 0.04);
  const auto model = scaleFor(0.2, 400, 400, 7, 1.0, 5e-6);
  ASSERT_TRUE(model.has_value());
  EXPECT_DOUBLE_EQ(*model, 1.0);
  // An overconfident ICP reads the same whatever the least scale.
  EXPECT_NEAR(*scaleFor(50.0, 400, 400, 9, 0.04), *scaleFor(50.0, 400, 400, 9), 0.01 * 50);
  EXPECT_THROW(CIcpConsistency(30, 10, 0.0), std::invalid_argument);
  EXPECT_THROW(CIcpConsistency(30, 10, 1.5), std::invalid_argument);
}

TEST(IcpConsistency, BelowOneAShareOfThePairsIsNoiseAlone)
{
  // Below 1 the error is noise alone: a run on share q, claiming Si / q,
  // has covariance k Si / q, its claim scaled by k, and it keeps q of the
  // information. Runs on all the pairs and on a quarter, interleaved, give
  // back the k of all the pairs.
  std::mt19937 rng(10);
  const double truth = 0.25;
  CIcpConsistency c(400, 10, 0.04);
  for (int i = 0; i < 400; ++i)
  {
    const Matrix6d Sf = randomCovariance(rng, 1e-6);
    const Matrix6d Si = randomCovariance(rng, 1e-6);
    const double q = i % 2 ? 0.25 : 1.0;
    c.add(draw(rng, Sf + truth * Si / q), Sf, Si / q, q);
  }
  ASSERT_TRUE(c.scale().has_value());
  EXPECT_GT(*c.scale(), truth / 1.5);
  EXPECT_LT(*c.scale(), truth * 1.5);
  EXPECT_DOUBLE_EQ(*c.scaleFor(0.25), *c.scale());
  EXPECT_DOUBLE_EQ(c.informationKept(0.25), 0.25);
  EXPECT_DOUBLE_EQ(c.informationKept(1.0), 1.0);
}

TEST(IcpConsistency, IcpBetterDeterminedScalesIcpsCovarianceByTheMeasuredScale)
{
  using roislam::frontend::TInformation66;
  using roislam::frontend::detail::icpBetterDetermined;
  // Isotropic estimates: sigma_t in metres, 0.1 deg in rotation.
  const auto info = [](double sigmaT)
  {
    TInformation66 m;
    m.setZero();
    const double sr = 0.1 * M_PI / 180;
    for (int i = 0; i < 3; ++i)
    {
      m(i, i) = 1 / (sigmaT * sigmaT);
      m(i + 3, i + 3) = 1 / (sr * sr);
    }
    return m;
  };
  // ICP claims 1.2 mm, the chain 8 mm (a bridged frame on a rendered loop).
  const TInformation66 icp = info(0.0012), chain = info(0.008);
  EXPECT_TRUE(icpBetterDetermined(icp, 2.3, chain));     // ICP agrees with the features
  EXPECT_TRUE(icpBetterDetermined(icp, 40.0, chain));    // 1.2 mm x sqrt(40) = 7.6 mm
  EXPECT_FALSE(icpBetterDetermined(icp, 100.0, chain));  // 12 mm
  EXPECT_FALSE(icpBetterDetermined(icp, std::numeric_limits<double>::infinity(), chain));
  EXPECT_FALSE(icpBetterDetermined(icp, 0.0, chain));
  // A singular estimate loses; ICP singular: the other is kept.
  TInformation66 singular = chain;
  singular(0, 0) = 0;
  EXPECT_TRUE(icpBetterDetermined(icp, 40.0, singular));
  EXPECT_FALSE(icpBetterDetermined(singular, 1.0, chain));
}

namespace
{
/** Comparisons drawn with the features' covariance truly a times its claim
 *  and ICP's b times; every tenth one a gross outlier (x20) when asked. */
std::vector<CIcpConsistency::TComparison> jointSamples(
    double a, double b, int n, unsigned seed, bool outliers = false)
{
  std::mt19937 rng(seed);
  std::vector<CIcpConsistency::TComparison> out;
  for (int i = 0; i < n; ++i)
  {
    const Matrix6d Sf = randomCovariance(rng, 1e-6);
    const Matrix6d Si = randomCovariance(rng, 1e-6);
    Vector6d d = draw(rng, a * Sf + b * Si);
    if (outliers && i % 10 == 9)
      d *= 20;
    out.push_back({d, Sf, Si, 1.0});
  }
  return out;
}
}  // namespace

TEST(IcpConsistency, JointFitRecoversBothEstimatorsScales)
{
  // Which of the two is off, and by how much, in either direction.
  for (const auto& [a, b] : {std::pair{0.15, 0.1}, {8.0, 0.2}, {0.5, 20.0}, {1.0, 1.0}})
  {
    SCOPED_TRACE(testing::Message() << "features x" << a << ", ICP x" << b);
    const auto s = CIcpConsistency::fitJointScales(jointSamples(a, b, 300, 11));
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(std::log(s->features), std::log(a), std::log(1.25));
    EXPECT_NEAR(std::log(s->icp), std::log(b), std::log(1.25));
    // The one-scale model books it all against ICP: it cannot see a.
  }
  // The front end's window of 30 is noisier. The features' scale is still
  // of the right order; ICP's, whose part of the disagreement is 40x the
  // smaller there, only on the right side of its claim.
  const auto s = CIcpConsistency::fitJointScales(jointSamples(8.0, 0.2, 30, 12));
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(std::log(s->features), std::log(8.0), std::log(2.0));
  EXPECT_LT(s->icp, 1.0);
}

TEST(IcpConsistency, JointFitIsNotSetByAFewWrongMatches)
{
  // One comparison in ten 20x off (a wrong match): the Student-t keeps the
  // fit within 40 %, where a Gaussian would read about 40x.
  const auto s = CIcpConsistency::fitJointScales(jointSamples(2.0, 0.5, 300, 13, true));
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(std::log(s->features), std::log(2.0), std::log(1.4));
  EXPECT_NEAR(std::log(s->icp), std::log(0.5), std::log(1.4));
}

TEST(IcpConsistency, JointScalesOnlyOnceTheWindowIsFullAndBounded)
{
  CIcpConsistency c(30, 10, 0.04);
  const auto samples = jointSamples(3.0, 0.3, 30, 14);
  for (std::size_t i = 0; i + 1 < samples.size(); ++i)
    c.add(samples[i].d, samples[i].featureCov, samples[i].icpCov);
  EXPECT_TRUE(c.scale().has_value());
  EXPECT_FALSE(c.jointScales().has_value());
  c.add(samples.back().d, samples.back().featureCov, samples.back().icpCov);
  ASSERT_TRUE(c.jointScales().has_value());
  EXPECT_GT(c.jointScales()->features, 1.5);
  c.reset();
  EXPECT_FALSE(c.jointScales().has_value());
  // Fewer than two comparisons: no fit. Disagreements far beyond either
  // claim: the fit stops at its bound (e^7, over the Student-t's 0.8167)
  // instead of running away.
  EXPECT_FALSE(CIcpConsistency::fitJointScales({}).has_value());
  const auto far = CIcpConsistency::fitJointScales(jointSamples(1e6, 1e6, 40, 15));
  ASSERT_TRUE(far.has_value());
  EXPECT_LE(far->features, std::exp(7.0) / 0.8167 * 1.001);
  EXPECT_LE(far->icp, std::exp(7.0) / 0.8167 * 1.001);
}

TEST(IcpConsistency, JointFitFromThePreviousOneFindsTheSameScales)
{
  // The front end searches from the last fit (the window moved by one):
  // the same optimum as from the grid, within the search's 0.1 %.
  const auto samples = jointSamples(0.3, 4.0, 30, 16);
  const auto cold = CIcpConsistency::fitJointScales(samples);
  ASSERT_TRUE(cold.has_value());
  const auto warm = CIcpConsistency::fitJointScales(
      samples, CIcpConsistency::TJointScales{cold->features * 1.3, cold->icp / 1.3});
  ASSERT_TRUE(warm.has_value());
  EXPECT_NEAR(warm->features / cold->features, 1.0, 0.01);
  EXPECT_NEAR(warm->icp / cold->icp, 1.0, 0.01);
}
