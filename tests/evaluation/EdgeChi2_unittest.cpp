/* evaluation::edgeChi2: edges drawn from their own information, as SPA
 * parametrises it (pseudo-log of the right perturbation), give chi² with mean
 * 6 and median 5.35; the same edges claiming 10x the information read 10x as
 * high; exact edges read 0 (MRPT's own SO(3) log gives NaN there); nodes
 * without ground truth are skipped. */
#include <gtest/gtest.h>
#include <roislam/evaluation/EdgeChi2.h>
#include <roislam/geometry/Rotation.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

namespace evaluation = roislam::evaluation;
using mrpt::poses::CPose3D;

namespace
{
/** truth exp(e): the right perturbation SPA's residual is the log of. */
CPose3D perturbRight(const CPose3D& truth, const Eigen::Matrix<double, 6, 1>& e)
{
  mrpt::math::CMatrixDouble33 R;
  R.asEigen() = roislam::geometry::expSO3(e.tail<3>());
  const CPose3D E(R, mrpt::math::CVectorFixedDouble<3>(Eigen::Vector3d(e.head<3>())));
  return truth + E;
}

/** An edge claiming sigmaM per translation axis and sigmaRad per rotation
 *  axis, uncorrelated: its information, and errors drawn from it. */
struct TAxisSigmas
{
  double sigmaM = 0, sigmaRad = 0;
  double sigma(int k) const { return k < 3 ? sigmaM : sigmaRad; }
  mrpt::math::CMatrixDouble66 information() const
  {
    mrpt::math::CMatrixDouble66 I;
    I.setZero();
    for (int k = 0; k < 6; ++k)
      I(k, k) = 1.0 / std::pow(sigma(k), 2);
    return I;
  }
  Eigen::Matrix<double, 6, 1> draw(std::mt19937& rng, std::normal_distribution<double>& N) const
  {
    Eigen::Matrix<double, 6, 1> z;
    for (int k = 0; k < 6; ++k)
      z[k] = sigma(k) * N(rng);
    return z;
  }
};

struct TGraphWithTruth
{
  mrpt::graphs::CNetworkOfPoses3DInf graph;
  roislam::io::TTrajectory gt;
};

TGraphWithTruth noisyChain(std::size_t n, double informationScale)
{
  std::mt19937 rng(7);
  std::normal_distribution<double> N(0, 1);
  // A covariance with correlations between translation and rotation.
  Eigen::Matrix<double, 6, 6> L = Eigen::Matrix<double, 6, 6>::Zero();
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c <= r; ++c)
      L(r, c) = r == c ? (r < 3 ? 0.004 : 0.002) : 0.0005 * (r + c);
  const Eigen::Matrix<double, 6, 6> info = (L * L.transpose()).inverse();
  TGraphWithTruth g;
  for (std::size_t i = 0; i <= n; ++i)
  {
    const double a = 0.05 * static_cast<double>(i);
    g.gt.push_back({static_cast<double>(i), CPose3D(std::cos(a), std::sin(a), 0.1 * a, a, 0.1, 0)});
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const CPose3D truth = g.gt[i + 1].pose - g.gt[i].pose;
    Eigen::Matrix<double, 6, 1> z;
    for (int k = 0; k < 6; ++k)
      z[k] = N(rng);
    mrpt::math::CMatrixDouble66 I;
    I.asEigen() = informationScale * info;
    g.graph.insertEdgeAtEnd(
        i, i + 1, mrpt::poses::CPose3DPDFGaussianInf(perturbRight(truth, -(L * z)), I));
  }
  return g;
}

double stampOf(mrpt::graphs::TNodeID id)
{
  return static_cast<double>(id);
}
}  // namespace

TEST(EdgeChi2, EdgesDrawnFromTheirInformationReadChi2Of6)
{
  const auto g = noisyChain(4000, 1.0);
  const auto s = evaluation::edgeChi2(g.graph, stampOf, g.gt);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->edges, 4000u);
  EXPECT_EQ(s->skipped, 0u);
  EXPECT_NEAR(s->mean, 6.0, 0.3);
  EXPECT_NEAR(s->median, 5.35, 0.3);
  // Each direction's e_i^2 / Sigma_ii has mean 1.
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(s->direction[k], 1.0, 0.1) << "direction " << k;
  // Labelled edges: the same statistics per kind.
  const auto byParity = evaluation::edgeChi2(
      g.graph, stampOf, g.gt, 0.02,
      [](mrpt::graphs::TNodeID from, mrpt::graphs::TNodeID) -> std::string
      { return from % 2 ? "odd" : "even"; });
  ASSERT_TRUE(byParity);
  ASSERT_EQ(byParity->byKind.size(), 2u);
  EXPECT_EQ(byParity->byKind.at("odd").edges, 2000u);
  EXPECT_NEAR(byParity->byKind.at("even").mean, 6.0, 0.45);
  EXPECT_NEAR(byParity->byKind.at("odd").direction[3], 1.0, 0.15);
  // Overconfident edges read as such.
  const auto over = evaluation::edgeChi2(noisyChain(4000, 10.0).graph, stampOf, g.gt);
  ASSERT_TRUE(over);
  EXPECT_NEAR(over->mean, 60.0, 3.0);
  // The likelihood: 0.5 (chi² + log det Σ) + 3 log 2π per edge, Σ = L L^T
  // (lower triangular: log det Σ = 2 sum log L_ii); too tight and too wide
  // both read higher.
  double logDet = 0;
  for (int r = 0; r < 6; ++r)
    logDet += 2 * std::log(r < 3 ? 0.004 : 0.002);
  EXPECT_NEAR(s->nll, 0.5 * (6.0 + logDet) + 3 * std::log(2 * M_PI), 0.15);
  const auto wide = evaluation::edgeChi2(noisyChain(4000, 0.25).graph, stampOf, g.gt);
  ASSERT_TRUE(wide);
  EXPECT_GT(over->nll, s->nll + 1.0);
  EXPECT_GT(wide->nll, s->nll + 1.0);
  EXPECT_TRUE(evaluation::toJson(*s).at("nll").is_number());
}

TEST(EdgeChi2, ExactEdgesAndMissingGroundTruth)
{
  auto g = noisyChain(10, 1.0);
  for (auto& [ids, e] : g.graph.edges)
    e.mean = g.gt[ids.second].pose - g.gt[ids.first].pose;
  const auto s = evaluation::edgeChi2(g.graph, stampOf, g.gt);
  ASSERT_TRUE(s);
  EXPECT_LT(s->mean, 1e-12);
  // Node 0 has no ground truth within 0.02 s: its edge is skipped.
  const auto shifted = evaluation::edgeChi2(
      g.graph, [](mrpt::graphs::TNodeID id) { return id == 0 ? -5.0 : stampOf(id); }, g.gt);
  ASSERT_TRUE(shifted);
  EXPECT_EQ(shifted->skipped, 1u);
  EXPECT_EQ(shifted->edges, 9u);
  EXPECT_FALSE(evaluation::edgeChi2(g.graph, stampOf, roislam::io::TTrajectory{}));
  const auto j = evaluation::toJson(*s);
  EXPECT_EQ(j.at("edges").get<std::size_t>(), 10u);
  EXPECT_DOUBLE_EQ(j.at("expected").get<double>(), 6.0);
  EXPECT_EQ(j.at("direction").size(), 6u);
  EXPECT_TRUE(j.at("by_kind").empty());
}

/* A ground truth with its own white noise (1 mm, 0.1 deg per sample, at
 * 100 Hz on a smooth path): groundTruthNoise measures it, edges drawn from
 * their own information read high against it, and with its covariance added
 * read chi²(6) again. */
TEST(EdgeChi2, TheGroundTruthsOwnNoiseIsMeasuredAndAccountedFor)
{
  std::mt19937 rng(11);
  std::normal_distribution<double> N(0, 1);
  const double sigmaM = 0.001, sigmaRad = 0.1 * M_PI / 180;
  const TAxisSigmas gtNoise{sigmaM, sigmaRad};
  std::vector<CPose3D> path;
  roislam::io::TTrajectory gt;
  for (int i = 0; i < 3000; ++i)
  {
    const double t = 0.01 * i, a = 0.4 * t;
    path.emplace_back(std::cos(a), std::sin(a), 0.05 * t, a, 0.2 * std::sin(0.3 * t), 0.1);
    gt.push_back({t, perturbRight(path.back(), gtNoise.draw(rng, N))});
  }
  const auto noise = evaluation::groundTruthNoise(gt);
  ASSERT_TRUE(noise);
  EXPECT_NEAR(noise->sigmaM, sigmaM, 0.05 * sigmaM);
  EXPECT_NEAR(noise->sigmaRad, sigmaRad, 0.05 * sigmaRad);
  EXPECT_GT(noise->triplets, 2900u);

  // Keyframe edges every 10 samples (10 cm apart), claiming 0.5 mm and
  // 0.02 deg: far more precise than the ground truth.
  const TAxisSigmas claim{0.0005, 0.02 * M_PI / 180};
  const mrpt::math::CMatrixDouble66 I = claim.information();
  mrpt::graphs::CNetworkOfPoses3DInf graph;
  for (std::size_t i = 0; i + 10 < path.size(); i += 10)
  {
    const Eigen::Matrix<double, 6, 1> z = claim.draw(rng, N);
    graph.insertEdgeAtEnd(
        i / 10, i / 10 + 1,
        mrpt::poses::CPose3DPDFGaussianInf(perturbRight(path[i + 10] - path[i], z), I));
  }
  const auto s = evaluation::edgeChi2(
      graph, [](mrpt::graphs::TNodeID id) { return 0.1 * static_cast<double>(id); }, gt);
  ASSERT_TRUE(s && s->withGroundTruthNoise);
  EXPECT_GT(s->mean, 60.0);  // the ground truth's noise read as the edges'
  EXPECT_NEAR(s->withGroundTruthNoise->mean, 6.0, 0.6);
  EXPECT_NEAR(s->withGroundTruthNoise->median, 5.35, 0.6);
  const auto j = evaluation::toJson(*s);
  EXPECT_NEAR(j.at("ground_truth_noise").at("sigma_deg").get<double>(), 0.1, 0.005);
  EXPECT_TRUE(j.at("with_ground_truth_noise").is_object());
  // Per kind as well: each half of the edges reads chi²(6) with the noise.
  const auto byHalf = evaluation::edgeChi2(
      graph, [](mrpt::graphs::TNodeID id) { return 0.1 * static_cast<double>(id); }, gt, 0.02,
      [](mrpt::graphs::TNodeID from, mrpt::graphs::TNodeID) -> std::string
      { return from < 150 ? "first" : "second"; });
  ASSERT_TRUE(byHalf);
  ASSERT_EQ(byHalf->byKindWithGroundTruthNoise.size(), 2u);
  for (const auto& [k, st] : byHalf->byKindWithGroundTruthNoise)
  {
    EXPECT_EQ(st.edges, byHalf->byKind.at(k).edges) << k;
    EXPECT_GT(byHalf->byKind.at(k).mean, 60.0) << k;
    EXPECT_NEAR(st.mean, 6.0, 0.9) << k;
  }
  EXPECT_TRUE(evaluation::toJson(*byHalf)
                  .at("by_kind")
                  .at("first")
                  .at("with_ground_truth_noise")
                  .is_object());

  // A ground truth too sparse to measure: no second set.
  EXPECT_FALSE(evaluation::groundTruthNoise({gt.begin(), gt.begin() + 5}));
}

/* Frames stamped with 2 ms of white jitter (a driver's arrival times) on a
 * camera turning at 1 rad/s and moving at 0.5 m/s, against an exact ground
 * truth: stampJitter measures the jitter from the stamps alone, edges
 * between the true exposure times read high against the ground truth at the
 * stamps, and chi²(6) again with the jitter's term; a dropped frame breaks
 * no measurement. */
TEST(EdgeChi2, TheFramesStampJitterIsMeasuredAndAccountedFor)
{
  std::mt19937 rng(5);
  std::normal_distribution<double> N(0, 1);
  const auto poseAt = [](double t)
  { return CPose3D(0.5 * t, 0.1 * std::sin(t), 0.05 * t, t, 0.3 * std::sin(2 * t), 0.1 * t); };
  roislam::io::TTrajectory gt;
  for (int i = 0; i < 4000; ++i)
    gt.push_back({0.005 * i, poseAt(0.005 * i)});

  const double jitter = 0.002;
  std::vector<double> exposure, stamps;
  for (int i = 0; i < 500; ++i)
  {
    if (i % 50 == 25)
      continue;  // a dropped frame
    exposure.push_back(1.0 + i / 30.0);
    stamps.push_back(exposure.back() + jitter * N(rng));
  }
  const auto measured = evaluation::stampJitter(stamps);
  ASSERT_TRUE(measured);
  EXPECT_NEAR(measured->sigmaS, jitter, 0.1 * jitter);
  EXPECT_FALSE(evaluation::stampJitter({stamps.begin(), stamps.begin() + 8}));
  EXPECT_FALSE(evaluation::stampJitter(std::vector<double>(50, 1.0)));  // one stamp for all

  // Consecutive frames' edges, claiming 1 mm and 0.05 deg, measured between
  // the true exposure times.
  const TAxisSigmas claim{0.001, 0.05 * M_PI / 180};
  const mrpt::math::CMatrixDouble66 I = claim.information();
  mrpt::graphs::CNetworkOfPoses3DInf graph;
  for (std::size_t i = 0; i + 1 < exposure.size(); ++i)
  {
    const Eigen::Matrix<double, 6, 1> z = claim.draw(rng, N);
    graph.insertEdgeAtEnd(
        i, i + 1,
        mrpt::poses::CPose3DPDFGaussianInf(
            perturbRight(poseAt(exposure[i + 1]) - poseAt(exposure[i]), z), I));
  }
  const auto stampOf = [&stamps](mrpt::graphs::TNodeID id) { return stamps[id]; };
  const auto without = evaluation::edgeChi2(graph, stampOf, gt);
  const auto with = evaluation::edgeChi2(graph, stampOf, gt, 0.02, {}, stamps);
  ASSERT_TRUE(without && without->withGroundTruthNoise && with && with->withGroundTruthNoise);
  EXPECT_GT(without->withGroundTruthNoise->median, 10.0);  // the jitter read as the edges'
  EXPECT_NEAR(with->withGroundTruthNoise->mean, 6.0, 0.8);
  EXPECT_NEAR(with->withGroundTruthNoise->median, 5.35, 0.8);
  EXPECT_NEAR(with->groundTruthNoise->stampJitterS, jitter, 0.1 * jitter);
  EXPECT_NEAR(
      evaluation::toJson(*with).at("ground_truth_noise").at("stamp_jitter_ms").get<double>(), 2.0,
      0.2);

  // The twist the jitter moves a pose by: 1 rad/s about z at t = 0 (yaw).
  const auto twist = evaluation::groundTruthTwist(gt, 5.0);
  ASSERT_TRUE(twist);
  EXPECT_GT(twist->tail<3>().norm(), 0.9);
  EXPECT_FALSE(evaluation::groundTruthTwist(gt, 100.0));
}
