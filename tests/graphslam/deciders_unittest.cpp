/* Our node / edge registration deciders fed synthetic RGB-D observations of a
 * textured wall with known camera poses: nodes are registered exactly for new
 * keyframes (two at the first registration, as MRPT's engine requires),
 * odometry and recent-keyframe edges are added, the return trip produces a
 * verified loop closure, and the optimised graph matches the ground truth. */
#include <gtest/gtest.h>
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>
#include <roislam/io/ObservationConversion.h>

#include "SyntheticPlane.h"

namespace graphslam = roislam::graphslam;
namespace io = roislam::io;

namespace
{
graphslam::CSlamContext::TConfig testConfig()
{
  graphslam::CSlamContext::TConfig c;
  c.backEnd.loop_min_keyframe_gap = 3;
  c.backEnd.landmark_loops = false;  // proximity only: deterministic on a plane
  c.frontEnd.extractor.max_features = 800;
  return c;
}
}  // namespace

TEST(Deciders, RegisterKeyframeNodesEdgesAndLoopClosure)
{
  const roislam::testing::CSyntheticPlane plane;
  auto ctx = std::make_shared<graphslam::CSlamContext>(testConfig());
  graphslam::TGraph graph;
  graphslam::CKeyframeNRD nrd(ctx);
  graphslam::CKeyframeERD erd(ctx);
  nrd.setGraphPtr(&graph);
  erd.setGraphPtr(&graph);

  std::size_t registrations = 0;
  for (int i = 0; i <= 40; ++i)
  {
    const auto frame = plane.render(roislam::testing::outAndBackPose(i), i, 0.1 * i);
    // Through MRPT's interface: a CObservation3DRangeScan, as the engine gives it.
    mrpt::obs::CObservation::Ptr obs = io::frameToObservation(frame);
    const std::size_t nodesBefore = graph.nodes.size();
    const bool added = nrd.updateState(nullptr, nullptr, obs);
    erd.updateState(nullptr, nullptr, obs);
    const auto& r = *ctx->lastFrame();
    ASSERT_TRUE(r.pose) << "frame " << i;
    EXPECT_EQ(added, r.isNewKeyframe && r.newKeyframeId > 0) << "frame " << i;
    if (added)
    {
      ++registrations;
      EXPECT_EQ(graph.nodes.size() - nodesBefore, registrations == 1 ? 2u : 1u);
      EXPECT_TRUE(graph.nodes.count(r.newKeyframeId));
    }
  }
  const auto& kfs = ctx->odometry().keyframes();
  EXPECT_GE(kfs.size(), 6u);  // 1.2 m of travel, a keyframe every 0.10 m
  EXPECT_EQ(graph.nodes.size(), kfs.size());
  EXPECT_GE(graph.edges.size(), graph.nodes.size() - 1);
  // Returning over the outbound keyframes closes at least one loop.
  ASSERT_GE(ctx->loopClosures().size(), 1u);
  for (const auto& lc : ctx->loopClosures())
    EXPECT_GE(lc.toKeyframe, lc.fromKeyframe + 3);
  std::map<std::string, int> stats;
  erd.getEdgesStats(&stats);
  EXPECT_EQ(stats["lc"], static_cast<int>(ctx->loopClosures().size()));
  EXPECT_GE(erd.edgeCounts().at("loop_proximity"), 1);

  ctx->optimize(graph);
  ctx->correctFrontEnd(graph);
  for (const auto& [id, pose] : graph.nodes)
  {
    const auto truth = roislam::testing::outAndBackPose(static_cast<int>(kfs[id].frameIndex));
    EXPECT_LT((pose.translation() - truth.translation()).norm(), 0.01)
        << "node " << id << " " << pose << " truth " << truth;
  }
}

TEST(Deciders, NoNodeWithoutMotion)
{
  const roislam::testing::CSyntheticPlane plane;
  auto ctx = std::make_shared<graphslam::CSlamContext>(testConfig());
  graphslam::TGraph graph;
  graphslam::CKeyframeNRD nrd(ctx);
  nrd.setGraphPtr(&graph);
  for (int i = 0; i < 5; ++i)
  {
    const auto r = ctx->odometry().process(plane.render(mrpt::poses::CPose3D(), i, 0.1 * i));
    EXPECT_FALSE(nrd.registerFrame(r));
  }
  EXPECT_TRUE(graph.nodes.empty());
  // Observations of other kinds are ignored.
  EXPECT_FALSE(nrd.updateState(nullptr, nullptr, nullptr));
}

TEST(Deciders, RegisteredByNameWithDescriptions)
{
  graphslam::CRoislamOptionsChecker checker;
  EXPECT_TRUE(checker.node_regs_map.count("CKeyframeNRD"));
  EXPECT_TRUE(checker.edge_regs_map.count("CKeyframeERD"));
  EXPECT_TRUE(checker.optimizers_map.count("CKeyframeGSO"));
  const std::string nodes = checker.describeRegistrars("node");
  EXPECT_NE(nodes.find("CKeyframeNRD: "), std::string::npos);
  EXPECT_EQ(nodes.find("CKeyframeERD"), std::string::npos);
  EXPECT_NE(checker.describeRegistrars("edge").find("CKeyframeERD: "), std::string::npos);
  // A factory-made decider works with the per-graph shared context.
  std::unique_ptr<mrpt::graphslam::deciders::CNodeRegistrationDecider<graphslam::TGraph>> nrd(
      checker.node_regs_map["CKeyframeNRD"]());
  graphslam::TGraph graph;
  nrd->setGraphPtr(&graph);
  EXPECT_TRUE(dynamic_cast<graphslam::CKeyframeNRD&>(*nrd).context());
  graphslam::CSlamContext::setForGraph(&graph, nullptr);
}
