/* CSlamContext::optimize on a synthetic keyframe graph: a noisy odometry chain
 * around a loop plus one loop-closure edge must move the nodes towards the
 * ground truth, and the optimised poses must reach the front end. */
#include <gtest/gtest.h>
#include <mrpt/poses/CPose3DPDFGaussianInf.h>
#include <mrpt/random/RandomGenerators.h>
#include <roislam/graphslam/CSlamContext.h>

#include <cmath>

using roislam::graphslam::CSlamContext;
using roislam::graphslam::TGraph;

namespace
{
mrpt::poses::CPose3D truePose(int i, int n)
{
  const double a = 2 * M_PI * i / n;
  return mrpt::poses::CPose3D(std::cos(a), std::sin(a), 0.1 * std::sin(a), a + M_PI / 2, 0, 0);
}

double positionRmse(const TGraph& g, int n)
{
  double s = 0;
  for (int i = 0; i < n; ++i)
    s += (g.nodes.at(i).translation() - truePose(i, n).translation()).sqrNorm();
  return std::sqrt(s / n);
}
}  // namespace

TEST(Optimizer, LoopClosureReducesError)
{
  const int n = 40;
  auto& rng = mrpt::random::getRandomGenerator();
  rng.randomize(7);
  TGraph g;
  g.root = 0;
  g.nodes[0] = truePose(0, n);
  mrpt::math::CMatrixDouble66 info;
  info.setIdentity();
  for (int k = 0; k < 3; ++k)
    info(k, k) = 1.0 / (0.01 * 0.01);
  for (int k = 3; k < 6; ++k)
    info(k, k) = 1.0 / (0.005 * 0.005);
  for (int i = 1; i < n; ++i)
  {
    const auto rel = truePose(i, n) - truePose(i - 1, n);
    // Biased, noisy odometry (drift) as a front end would give.
    const mrpt::poses::CPose3D noisy =
        rel + mrpt::poses::CPose3D(
                  0.01 + rng.drawGaussian1D(0, 0.01), rng.drawGaussian1D(0, 0.01), 0, 0.01, 0, 0);
    g.nodes[i] = g.nodes[i - 1] + noisy;
    g.insertEdgeAtEnd(i - 1, i, mrpt::poses::CPose3DPDFGaussianInf(noisy, info));
  }
  const double before = positionRmse(g, n);
  // Loop closure: last node seen from the first.
  const auto lc = truePose(n - 1, n) - truePose(0, n);
  g.insertEdgeAtEnd(0, n - 1, mrpt::poses::CPose3DPDFGaussianInf(lc, info));

  CSlamContext ctx;
  const auto rep = ctx.optimize(g);
  const double after = positionRmse(g, n);
  EXPECT_GT(rep.iterations, 0u);
  EXPECT_LT(rep.chi2After, 0.1 * rep.chi2Before);
  EXPECT_LT(after, 0.5 * before) << "before " << before << " after " << after;
}
