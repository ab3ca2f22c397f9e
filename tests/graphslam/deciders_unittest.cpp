/* Our node / edge registration deciders fed synthetic RGB-D observations of a
 * textured wall with known camera poses: nodes are registered exactly for new
 * keyframes (two at the first registration, as MRPT's engine requires),
 * odometry and recent-keyframe edges are added, the return trip produces a
 * verified loop closure, and the optimised graph matches the ground truth. */
#include <gtest/gtest.h>
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeGSO.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>
#include <roislam/io/ObservationConversion.h>

#include <memory>
#include <stdexcept>

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
  // MRPT's own are listed with the reason they cannot run here.
  EXPECT_NE(
      nodes.find("not usable here:\nCFixedIntervalsNRD: registers nodes from odometry"),
      std::string::npos)
      << nodes;
  EXPECT_TRUE(checker.refusal("edge", "CEmptyERD").empty());
  EXPECT_TRUE(checker.refusal("optimizer", "CLevMarqGSO").empty());
  EXPECT_NE(checker.refusal("edge", "CICPCriteriaERD").find("2-D"), std::string::npos);
  EXPECT_NE(checker.refusal("node", "CNoSuchNRD").find("unknown"), std::string::npos);
  EXPECT_NE(checker.refusal("optimizer", "CEmptyGSO").find("abstract"), std::string::npos);
  EXPECT_THROW(
      checker.createDeciders({"CKeyframeNRD", "CLoopCloserERD", "CKeyframeGSO"}),
      std::invalid_argument);

  // MRPT's by-name factories cannot share a context: a decider made by one
  // alone says so instead of running without one.
  std::unique_ptr<mrpt::graphslam::deciders::CNodeRegistrationDecider<graphslam::TGraph>> lone(
      checker.node_regs_map["CKeyframeNRD"]());
  graphslam::TGraph graph;
  lone->setGraphPtr(&graph);
  const roislam::testing::CSyntheticPlane plane;
  mrpt::obs::CObservation::Ptr obs = io::frameToObservation(plane.render({}, 0, 0));
  try
  {
    lone->updateState(nullptr, nullptr, obs);
    FAIL() << "expected an error";
  }
  catch (const std::logic_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("createDeciders"), std::string::npos) << e.what();
  }

  // The factory's three share one context, and nothing else holds it.
  auto d = checker.createDeciders({});
  ASSERT_TRUE(d.ourNode() && d.ourEdge() && d.ourOptimizer());
  EXPECT_EQ(d.ourNode()->context(), d.context);
  EXPECT_EQ(d.ourEdge()->context(), d.context);
  EXPECT_EQ(d.ourOptimizer()->context(), d.context);
  EXPECT_EQ(d.context.use_count(), 4);
  const std::weak_ptr<graphslam::CSlamContext> weak = d.context;
  d = graphslam::TSlamDeciders();
  EXPECT_TRUE(weak.expired());
}
