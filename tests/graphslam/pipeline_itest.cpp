/* CSlamPipeline on the synthetic textured loop of the ctest fixture: every
 * frame gets a record and a pose; the optimisation policy ([GraphSlam]
 * optimize_min_chi2 / optimize_every_keyframes) optimises at every
 * loop-closing keyframe when both gates are at their minimum and only at the
 * end when they cannot trigger, with the same accuracy; windowed
 * optimisations (optimize_window_keyframes) move only the newest keyframes,
 * again with the same accuracy; and the ini keys of the back end are read
 * (loop_outlier_chi2 was once written but never read). */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/testing/TestData.h>

#include <cstdio>
#include <functional>
#include <limits>

namespace graphslam = roislam::graphslam;

namespace
{
struct TOutcome
{
  std::size_t frames = 0, posed = 0, loopKeyframes = 0, optimizations = 0, windowed = 0;
  double ate = 0;
};

TOutcome run(
    const std::string& seq, double minChi2, int every, int window = 0,
    const std::function<void(graphslam::CSlamContext::TConfig&)>& configure = {})
{
  graphslam::CSlamContext::TConfig cfg;
  cfg.frontEnd.extractor.feature_type = roislam::features::EFeatureType::ORB;
  cfg.frontEnd.extractor.max_features = 600;
  // The fixture's camera is rgbd-simul's Kinect-like rolling shutter, as in
  // the shipped configs.
  cfg.frontEnd.rolling_shutter_ms = 25;
  cfg.backEnd.optimize_min_chi2 = minChi2;
  cfg.backEnd.optimize_every_keyframes = every;
  cfg.backEnd.optimize_window_keyframes = window;
  if (configure)
    configure(cfg);
  auto source = roislam::io::CFrameSource::open(seq);
  const std::string gt = *source->groundTruthFile();
  graphslam::CSlamPipeline p(cfg, std::move(source));
  std::size_t loopsSeen = 0;
  TOutcome o;
  while (p.step())
  {
    if (p.context().loopClosures().size() > loopsSeen)
      ++o.loopKeyframes;
    loopsSeen = p.context().loopClosures().size();
  }
  p.finish();
  o.frames = p.records().size();
  const auto traj = p.trajectory();
  o.posed = traj.size();
  o.optimizations = p.optimizations().value();
  o.windowed = p.windowedOptimizations().value();
  o.ate = roislam::evaluation::CTrajectoryEvaluator()
              .evaluate(roislam::io::loadTumTrajectory(gt), traj)
              .ate.rmse;
  return o;
}
}  // namespace

TEST(SlamPipeline, OptimisationPolicyOnTheTexturedLoop)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  // Every loop-closing keyframe optimised (the graph here is far smaller
  // than 50 nodes, so no spacing applies), plus the final optimisation.
  const auto eager = run(seq, 0.0, 1);
  // Gates that never trigger: only the final optimisation.
  const auto lazy = run(seq, std::numeric_limits<double>::max(), 1000000);
  for (const auto* o : {&eager, &lazy})
  {
    EXPECT_EQ(o->posed, o->frames);
    EXPECT_LT(o->ate, 0.01);
  }
  std::printf(
      "eager: %zu loop-closing keyframes, %zu optimisations, ATE %.4f; lazy: %zu, ATE %.4f\n",
      eager.loopKeyframes, eager.optimizations, eager.ate, lazy.optimizations, lazy.ate);
  ASSERT_GT(eager.loopKeyframes, 0u);
  EXPECT_EQ(eager.optimizations, eager.loopKeyframes + 1);
  EXPECT_EQ(lazy.optimizations, 1u);
}

TEST(SlamPipeline, RegionModesOnTheTexturedLoop)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  // Both ROI modes describing their tracking region only, extended at half
  // resolution when a frame needs it (issue 15), and following the rest of
  // the image by optical flow instead (roi_extraction = flow): still within
  // 1 cm, with the keyframe policy the ROI configs ship (config/roi_*.ini:
  // 5 deg, 8 keyframes a place). At the library's 10 deg flow's big ROI
  // reads 0.0095 m with Shi-Tomasi anchors and 0.0101 m with the keyframe's
  // features (flow_anchors), the shipped policy 0.0076 m.
  for (const char* extraction : {"region", "flow"})
    for (const auto mode :
         {roislam::frontend::EFrontEndMode::RoiSmall, roislam::frontend::EFrontEndMode::RoiBig})
    {
      const auto o =
          run(seq, 0.0, 1, 0,
              [&](graphslam::CSlamContext::TConfig& cfg)
              {
                cfg.frontEnd.mode = mode;
                cfg.frontEnd.roi_extraction = extraction;
                cfg.frontEnd.roi_extension_scale = 0.5;
                cfg.frontEnd.keyframe_rotation_deg = 5;
                cfg.frontEnd.keyframe_place_limit = 8;
              });
      std::printf(
          "%s %s: ATE %.4f\n", roislam::frontend::toString(mode).c_str(), extraction, o.ate);
      EXPECT_EQ(o.posed, o.frames);
      EXPECT_LT(o.ate, 0.01) << roislam::frontend::toString(mode) << " " << extraction;
    }
}

TEST(SlamPipeline, WindowedOptimisationsMoveOnlyTheNewestKeyframes)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  graphslam::TGraph g;
  // A chain of 6 nodes whose last edge disagrees with the others: a window
  // of 2 may move only nodes 4 and 5.
  mrpt::math::CMatrixDouble66 inf;
  inf.setIdentity();
  inf *= 100;
  for (mrpt::graphs::TNodeID i = 0; i < 6; ++i)
    g.nodes[i] = mrpt::poses::CPose3D(0.1 * i, 0, 0, 0, 0, 0);
  for (mrpt::graphs::TNodeID i = 0; i + 1 < 6; ++i)
    g.insertEdgeAtEnd(
        i, i + 1,
        mrpt::poses::CPose3DPDFGaussianInf(mrpt::poses::CPose3D(0.1, 0, 0, 0, 0, 0), inf));
  g.insertEdgeAtEnd(
      0, 5, mrpt::poses::CPose3DPDFGaussianInf(mrpt::poses::CPose3D(0.6, 0, 0, 0, 0, 0), inf));
  graphslam::CSlamContext ctx;
  const auto before = g.nodes;
  const auto r = ctx.optimize(g, 2);
  EXPECT_EQ(r.freeNodes, 2u);
  for (mrpt::graphs::TNodeID i = 0; i < 4; ++i)
    EXPECT_EQ(g.nodes.at(i), before.at(i)) << "node " << i;
  EXPECT_GT(g.nodes.at(5).x(), 0.5 + 1e-4);
  EXPECT_LT(r.chi2After, r.chi2Before);
  // The whole graph moves without a window.
  const auto full = ctx.optimize(g);
  EXPECT_EQ(full.freeNodes, 5u);
  EXPECT_NE(g.nodes.at(2), before.at(2));

  // On the textured loop, windowed optimisations at every inconsistent
  // closure (window 5 of a graph several times larger) reach the same
  // accuracy; the whole graph is solved only at the end.
  const auto windowed = run(seq, 0.0, 1000000, 5);
  std::printf(
      "windowed: %zu optimisations (%zu windowed), ATE %.4f\n", windowed.optimizations,
      windowed.windowed, windowed.ate);
  EXPECT_EQ(windowed.posed, windowed.frames);
  EXPECT_LT(windowed.ate, 0.01);
  EXPECT_GT(windowed.windowed, 0u);
  EXPECT_EQ(windowed.optimizations, windowed.windowed + 1);
}

TEST(SlamPipeline, LoopDiscrepancyLimitGrowsWithThePath)
{
  // Keyframes 1 m apart along x: the limit between 2 and 7 is the fixed part
  // plus the per-metre share of the 5 m between them, in either order.
  graphslam::TGraph g;
  for (mrpt::graphs::TNodeID i = 0; i < 10; ++i)
    g.nodes[i] = mrpt::poses::CPose3D(1.0 * i, 0, 0, 0, 0, 0);
  graphslam::CSlamContext::TConfig cfg;
  cfg.backEnd.loop_max_discrepancy_m = 0.5;
  cfg.backEnd.loop_max_discrepancy_per_m = 0.05;
  const graphslam::CSlamContext ctx(cfg);
  EXPECT_NEAR(ctx.loopDiscrepancyLimit(2, 7, g), 0.75, 1e-12);
  EXPECT_NEAR(ctx.loopDiscrepancyLimit(7, 2, g), 0.75, 1e-12);
  EXPECT_NEAR(ctx.loopDiscrepancyLimit(4, 4, g), 0.5, 1e-12);
  // A missing node interrupts nothing else: the 1 m around it is not counted.
  g.nodes.erase(5);
  EXPECT_NEAR(ctx.loopDiscrepancyLimit(2, 7, g), 0.65, 1e-12);
  cfg.backEnd.loop_max_discrepancy_per_m = 0;
  EXPECT_NEAR(graphslam::CSlamContext(cfg).loopDiscrepancyLimit(0, 9, g), 0.5, 1e-12);
}

TEST(SlamPipeline, BackEndOptionsAreReadFromTheIni)
{
  mrpt::config::CConfigFileMemory ini;
  ini.write("GraphSlam", "loop_outlier_chi2", 12.5);
  ini.write("GraphSlam", "optimize_min_chi2", 7.0);
  ini.write("GraphSlam", "optimize_every_keyframes", 4);
  ini.write("GraphSlam", "optimize_window_keyframes", 0);
  ini.write("GraphSlam", "loop_max_discrepancy_per_m", 0.02);
  const auto c = graphslam::CSlamContext::loadConfig(ini, "test.ini");
  EXPECT_DOUBLE_EQ(c.backEnd.loop_outlier_chi2, 12.5);
  EXPECT_DOUBLE_EQ(c.backEnd.optimize_min_chi2, 7.0);
  EXPECT_EQ(c.backEnd.optimize_every_keyframes, 4);
  EXPECT_EQ(c.backEnd.optimize_window_keyframes, 0);
  EXPECT_DOUBLE_EQ(c.backEnd.loop_max_discrepancy_per_m, 0.02);
  const std::pair<std::string, std::string> bads[] = {
      {"optimize_every_keyframes", "0"},
      {"optimize_window_keyframes", "-1"},
      {"loop_max_discrepancy_per_m", "-0.1"},
      {"optimize_min_chi2", "-1"},
      {"edge_information", "isotropic"}};
  for (const auto& [key, value] : bads)
  {
    mrpt::config::CConfigFileMemory bad;
    bad.write("GraphSlam", key, value);
    try
    {
      graphslam::CSlamContext::loadConfig(bad, "bad.ini");
      FAIL() << "expected an exception for " << key;
    }
    catch (const std::exception& e)
    {
      EXPECT_NE(std::string(e.what()).find("[GraphSlam] " + key), std::string::npos) << e.what();
    }
  }
}
