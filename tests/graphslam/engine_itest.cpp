/* Our deciders inside MRPT's own CGraphSlamEngine<CNetworkOfPoses3DInf>,
 * headless: observations of the synthetic wall go through
 * execGraphSlamStep(); the engine's graph gets one node per keyframe and the
 * loop closure, and (after our final optimisation, since MRPT 2.5's engine
 * resets poses by Dijkstra) matches the ground truth. Then the same through
 * CRgbdGraphSlamEngine, which undoes that reset: its graph is the optimised
 * one after every step. Two runs by name in turn build the same graph, and
 * nothing of a run (its context) outlives its engine and deciders. */
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeGSO.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CRgbdGraphSlamEngine.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>  // CLevMarqGSO include fixes
#include <roislam/io/ObservationConversion.h>
#include <roislam/testing/TestData.h>

#include "SyntheticPlane.h"
//
#include <fcntl.h>
#include <gtest/gtest.h>
#include <mrpt/graphslam/CGraphSlamEngine.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

namespace graphslam = roislam::graphslam;

TEST(Engine, DecidersRunInsideCGraphSlamEngine)
{
  const std::string dir = roislam::testing::makeTempDir("graphslam_engine");
  const std::string ini = dir + "/engine.ini";
  {
    std::ofstream f(ini);
    f << "[GeneralConfiguration]\nuser_decides_about_output_dir = false\n"
         "save_map = false\nclass_verbosity = 3\n";
  }
  graphslam::CSlamContext::TConfig cfg;
  cfg.backEnd.loop_min_keyframe_gap = 3;
  cfg.backEnd.landmark_loops = false;
  // Optimise at every loop-closing keyframe.
  cfg.backEnd.optimize_min_chi2 = 0;
  cfg.backEnd.optimize_every_keyframes = 1;
  cfg.frontEnd.extractor.max_features = 800;
  auto ctx = std::make_shared<graphslam::CSlamContext>(cfg);
  graphslam::CKeyframeNRD nrd(ctx);
  graphslam::CKeyframeERD erd(ctx);
  graphslam::CKeyframeGSO gso(ctx);

  // MRPT 2.5's constructor waits for a key press (class-name mismatch): give
  // it /dev/null as stdin for the duration.
  const int savedStdin = dup(0);
  const int devNull = open("/dev/null", O_RDONLY);
  dup2(devNull, 0);
  auto engine = std::make_unique<mrpt::graphslam::CGraphSlamEngine<graphslam::TGraph>>(
      ini, "", "", nullptr, &nrd, &erd, &gso);
  dup2(savedStdin, 0);
  close(devNull);
  close(savedStdin);

  const roislam::testing::CSyntheticPlane plane;
  std::size_t entry = 0;
  for (int i = 0; i <= 40; ++i)
  {
    mrpt::obs::CObservation::Ptr obs = roislam::io::frameToObservation(
        plane.render(roislam::testing::outAndBackPose(i), i, 0.1 * i));
    ASSERT_TRUE(engine->execGraphSlamStep(obs, entry));
  }
  auto graph = engine->getGraph();
  const auto& kfs = ctx->odometry().keyframes();
  EXPECT_EQ(graph.nodes.size(), kfs.size());
  EXPECT_GE(ctx->loopClosures().size(), 1u);
  EXPECT_GE(gso.optimizations(), 1u);
  ctx->optimize(graph);
  for (const auto& [id, pose] : graph.nodes)
  {
    const auto truth = roislam::testing::outAndBackPose(static_cast<int>(kfs.at(id).frameIndex));
    EXPECT_LT((pose.translation() - truth.translation()).norm(), 0.01) << "node " << id;
  }
  engine.reset();
  std::filesystem::remove_all(dir);
}

TEST(Engine, RgbdEngineKeepsTheOptimisedPoses)
{
  const std::string dir = roislam::testing::makeTempDir("graphslam_rgbd_engine");
  const std::string ini = dir + "/engine.ini";
  {
    std::ofstream f(ini);
    f << "[GeneralConfiguration]\nclass_verbosity = 3\n"
         "[EdgeRegistrationDeciderParameters]\nloop_min_keyframe_gap = 3\nlandmark_loops = false\n"
         "[OptimizerParameters]\noptimize_min_chi2 = 0\noptimize_every_keyframes = 1\n"
         "[FeatureExtractor]\nmax_features = 800\n";
  }
  // By name, configured by the deciders' loadParams() from the ini.
  auto d = graphslam::CRoislamOptionsChecker().createDeciders({});
  auto engine = graphslam::CRgbdGraphSlamEngine::create(ini, d);
  EXPECT_EQ(d.context->config().backEnd.loop_min_keyframe_gap, 3);
  EXPECT_EQ(d.context->config().frontEnd.extractor.max_features, 800);
  const roislam::testing::CSyntheticPlane plane;
  std::size_t optimisedSteps = 0;
  for (int i = 0; i <= 40; ++i)
  {
    ASSERT_TRUE(engine->step(roislam::io::frameToObservation(
        plane.render(roislam::testing::outAndBackPose(i), i, 0.1 * i))));
    if (!d.ourOptimizer()->justFullyOptimizedGraph())
      continue;
    // MRPT 2.5 would have left the spanning-tree estimate: ours is better.
    auto tree = engine->getGraph();
    tree.dijkstra_nodes_estimate();
    EXPECT_LT(engine->getGraph().chi2(), tree.chi2()) << "frame " << i;
    ++optimisedSteps;
  }
  EXPECT_GE(optimisedSteps, 1u);
  d.ourOptimizer()->finish();
  const auto& kfs = d.context->odometry().keyframes();
  ASSERT_EQ(engine->getGraph().nodes.size(), kfs.size());
  for (const auto& [id, pose] : engine->getGraph().nodes)
  {
    const auto truth = roislam::testing::outAndBackPose(static_cast<int>(kfs.at(id).frameIndex));
    EXPECT_LT((pose.translation() - truth.translation()).norm(), 0.01) << "node " << id;
  }
  engine.reset();
  std::filesystem::remove_all(dir);
}

TEST(Engine, NoStateOutlivesTheEngine)
{
  const std::string dir = roislam::testing::makeTempDir("graphslam_engine_state");
  const std::string ini = dir + "/engine.ini";
  {
    std::ofstream f(ini);
    f << "[EdgeRegistrationDeciderParameters]\nloop_min_keyframe_gap = 3\nlandmark_loops = false\n"
         "[FeatureExtractor]\nmax_features = 800\n";
  }
  const roislam::testing::CSyntheticPlane plane;
  // Two runs one after the other, by name: the second starts from nothing the
  // first left (no registry, no static state), so it builds the same graph;
  // once the engine and the deciders are gone, so is their context.
  std::vector<graphslam::TGraph> graphs;
  for (int run = 0; run < 2; ++run)
  {
    auto d = graphslam::CRoislamOptionsChecker().createDeciders({});
    const std::weak_ptr<graphslam::CSlamContext> context = d.context;
    auto engine = graphslam::CRgbdGraphSlamEngine::create(ini, d);
    for (int i = 0; i <= 30; ++i)
      ASSERT_TRUE(engine->step(roislam::io::frameToObservation(
          plane.render(roislam::testing::outAndBackPose(i), i, 0.1 * i))));
    d.ourOptimizer()->finish();
    graphs.push_back(engine->getGraph());
    EXPECT_EQ(context.lock()->odometry().keyframes().size(), graphs.back().nodes.size());
    engine.reset();
    d = graphslam::TSlamDeciders();
    EXPECT_TRUE(context.expired()) << "run " << run;
  }
  ASSERT_GE(graphs[0].nodes.size(), 3u);
  EXPECT_EQ(graphs[0].nodes.size(), graphs[1].nodes.size());
  EXPECT_EQ(graphs[0].edgeCount(), graphs[1].edgeCount());
  for (const auto& [id, pose] : graphs[0].nodes)
    EXPECT_EQ(pose, graphs[1].nodes.at(id)) << "node " << id;
  std::filesystem::remove_all(dir);
}
