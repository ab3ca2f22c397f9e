// CRigidTransformRansac: recovers a known rigid transform from noisy 3-D
// correspondences with injected outliers, and rejects degenerate input.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/matching/CRigidTransformRansac.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

using mrpt::math::TPoint3D;
using mrpt::poses::CPose3D;
using roislam::matching::CRigidTransformRansac;

namespace
{
struct TData
{
  std::vector<TPoint3D> target, source;
  std::vector<bool> isInlier;
};

// target = truth (+) source + noise; `outlierRatio` of the pairs are random.
TData makeData(const CPose3D& truth, std::size_t n, double outlierRatio, double noise, int seed)
{
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::uniform_real_distribution<double> ux(-1.5, 1.5), uz(0.5, 4.0), uo(-2.0, 2.0);
  std::normal_distribution<double> gn(0.0, noise);
  TData d;
  for (std::size_t i = 0; i < n; ++i)
  {
    const TPoint3D s(ux(rng), ux(rng), uz(rng));
    TPoint3D t = truth.composePoint(s);
    const bool inl = static_cast<double>(i) >= outlierRatio * static_cast<double>(n);
    if (inl)
      t += TPoint3D(gn(rng), gn(rng), gn(rng));
    else
      t = TPoint3D(uo(rng), uo(rng), uz(rng));
    d.source.push_back(s);
    d.target.push_back(t);
    d.isInlier.push_back(inl);
  }
  return d;
}

double rotationErrorDeg(const CPose3D& a, const CPose3D& b)
{
  // A named copy: asEigen() on the temporary would dangle.
  const mrpt::math::CMatrixDouble33 R = (a - b).getRotationMatrix();
  return std::acos(std::clamp((R.trace() - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / M_PI;
}
}  // namespace

TEST(RigidRansac, RecoversTransformWith30PercentOutliers)
{
  const CPose3D truth(0.3, -0.2, 0.15, 0.4, -0.25, 0.1);
  const auto d = makeData(truth, 400, 0.3, 0.002, 7);
  CRigidTransformRansac ransac;
  const auto r = ransac.estimate(d.target, d.source);
  ASSERT_TRUE(r.has_value());
  EXPECT_LT((r->transform.translation() - truth.translation()).norm(), 1e-3);
  EXPECT_LT(rotationErrorDeg(r->transform, truth), 0.1);
  std::size_t wrong = 0;
  for (auto i : r->inliers)
    wrong += d.isInlier[i] ? 0 : 1;
  EXPECT_EQ(wrong, 0u);
  EXPECT_GE(r->inliers.size(), 270u);  // 280 true inliers, noise well below the gate
  EXPECT_LT(r->rmse, 0.006);
}

TEST(RigidRansac, ExactDataGivesExactTransform)
{
  const CPose3D truth(-1.0, 0.5, 2.0, -2.5, 0.3, 1.2);
  const auto d = makeData(truth, 50, 0.0, 0.0, 3);
  const auto r = CRigidTransformRansac().estimate(d.target, d.source);
  ASSERT_TRUE(r.has_value());
  EXPECT_LT((r->transform.translation() - truth.translation()).norm(), 1e-9);
  EXPECT_LT(rotationErrorDeg(r->transform, truth), 1e-5);
  EXPECT_EQ(r->inliers.size(), 50u);
}

TEST(RigidRansac, PureOutliersGiveNoResult)
{
  const auto d = makeData(CPose3D(), 100, 1.0, 0.0, 5);
  CRigidTransformRansac::TOptions o;
  o.min_inliers = 12;
  EXPECT_FALSE(CRigidTransformRansac(o).estimate(d.target, d.source).has_value());
}

TEST(RigidRansac, DegenerateInputs)
{
  // Collinear points: rotation about the line is undetermined.
  std::vector<TPoint3D> line;
  for (int i = 0; i < 10; ++i)
    line.emplace_back(0.1 * i, 0, 1);
  EXPECT_FALSE(CRigidTransformRansac().estimate(line, line).has_value());
  // Too few pairs and size mismatch.
  EXPECT_FALSE(CRigidTransformRansac().estimate({}, {}).has_value());
  EXPECT_THROW(CRigidTransformRansac().estimate(line, {}), std::invalid_argument);
}

TEST(RigidRansac, MinSampleSpreadAndSmallRegions)
{
  // 40 pairs within a 6 cm cube (a ROI's features), 4 cm inlier gate: the
  // default spread (2 x 4 cm) skips nearly every sample, 0 keeps them.
  const CPose3D truth(0.05, -0.02, 0.01, 0.1, 0.05, -0.03);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.03, 0.03);
  std::vector<TPoint3D> target, source;
  for (int i = 0; i < 40; ++i)
  {
    source.emplace_back(u(rng), u(rng), 1.5 + u(rng));
    target.push_back(truth.composePoint(source.back()));
  }
  CRigidTransformRansac::TOptions o;
  o.threshold_m = 0.04;
  EXPECT_FALSE(CRigidTransformRansac(o).estimate(target, source).has_value());
  o.min_sample_spread = 0;
  const auto r = CRigidTransformRansac(o).estimate(target, source);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->inliers.size(), 40u);
  EXPECT_LT((r->transform.translation() - truth.translation()).norm(), 1e-9);
  o.min_sample_spread = -1;
  EXPECT_THROW(CRigidTransformRansac{o}, std::invalid_argument);
}

TEST(RigidRansac, Deterministic)
{
  const auto d = makeData(CPose3D(0.1, 0.2, 0.3, 0.2, 0.1, 0.0), 200, 0.5, 0.005, 11);
  const auto a = CRigidTransformRansac().estimate(d.target, d.source);
  const auto b = CRigidTransformRansac().estimate(d.target, d.source);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->inliers, b->inliers);
  EXPECT_EQ(a->transform, b->transform);
}

TEST(RigidRansac, OptionsValidationAndIni)
{
  CRigidTransformRansac::TOptions o;
  o.threshold_m = 0;
  EXPECT_THROW(CRigidTransformRansac{o}, std::invalid_argument);
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("RigidRansac", "max_iterations", 0);
  CRigidTransformRansac::TOptions o2;
  try
  {
    o2.loadFromConfigFile(cfg, "RigidRansac");
    FAIL() << "expected an exception";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("[RigidRansac] max_iterations"), std::string::npos);
  }
  CRigidTransformRansac::TOptions o3;
  o3.threshold_m = 0.05;
  o3.seed = 42;
  o3.min_sample_spread = 0.5;
  mrpt::config::CConfigFileMemory out;
  o3.saveToConfigFile(out, "RigidRansac");
  CRigidTransformRansac::TOptions o4;
  o4.loadFromConfigFile(out, "RigidRansac");
  EXPECT_DOUBLE_EQ(o4.threshold_m, 0.05);
  EXPECT_EQ(o4.seed, 42u);
  EXPECT_DOUBLE_EQ(o4.min_sample_spread, 0.5);
}
