/* Our deciders inside MRPT's own CGraphSlamEngine<CNetworkOfPoses3DInf>,
 * headless: observations of the synthetic wall go through
 * execGraphSlamStep(); the engine's graph gets one node per keyframe and the
 * loop closure, and (after our final optimisation, since MRPT 2.5's engine
 * resets poses by Dijkstra) matches the ground truth. */
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeGSO.h>
#include <roislam/graphslam/CKeyframeNRD.h>
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
