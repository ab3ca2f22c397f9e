/* An error common to all keypoints of a frame, reproduced with rgbd-simul:
 * each frame's colour image shifted as a whole (common_shift_px, which the
 * sequence's camera.ini records as common_pixel_sigma_px). Registrations
 * average their keypoints' own noise down but not the shift, so edges that
 * ignore it claim far too much (fr1's symptom: chi² in the hundreds against
 * the ground truth); with the sensor's value their chi² is honest again and
 * the trajectory more accurate. */
#include <gtest/gtest.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/testing/TestData.h>

#include <cstdio>

#include "IclLikeRender.h"
#include "PipelineRuns.h"

namespace
{
struct TRunFigures
{
  double ate = 0, chi2Median = 0;
};

TRunFigures run(const std::string& seq, double modelCommonPx)
{
  auto cfg = roislam::testing::orbConfig();
  cfg.backEnd.edge_information = "estimator";
  // The shift under test. runPipeline applies the readout and the depth
  // noise; a render adds no keypoint noise of its own.
  cfg.frontEnd.common_pixel_sigma_px = modelCommonPx;
  const auto r = roislam::testing::runPipeline(seq, "auto", cfg);
  TRunFigures f;
  f.ate = r.ate.rmse;
  EXPECT_TRUE(r.edgeChi2);
  if (r.edgeChi2)
    f.chi2Median = r.edgeChi2->median;
  std::printf(
      "model %.2f px: ATE %.4f m, edge chi2 median %.2f\n", modelCommonPx, f.ate, f.chi2Median);
  return f;
}
}  // namespace

TEST(CommonShift, EdgesCarryTheShiftTheCameraDescribes)
{
  // rgbd-simul's ICL-like camera (global shutter, disparity noise), 1 px of
  // common shift per frame and axis.
  const roislam::testing::CTempDir dir("common_shift");
  const std::string seq = dir.path() + "/seq";
  roislam::testing::writeIclLikeRender(seq, [](auto& o) { o.commonShiftPx = 1.0; });
  // The camera describes its shift.
  EXPECT_DOUBLE_EQ(
      roislam::io::CFrameSource::open(seq)->sensor().sensor.common_pixel_sigma_px, 1.0);

  const TRunFigures ignored = run(seq, 0.0), carried = run(seq, 1.0);
  const double expectedMedian = 5.35;  // of chi²(6)
  EXPECT_GT(ignored.chi2Median, 4 * expectedMedian);
  EXPECT_GT(carried.chi2Median, expectedMedian / 2);
  EXPECT_LT(carried.chi2Median, expectedMedian * 2);
  EXPECT_LT(carried.ate, ignored.ate);
  EXPECT_LT(carried.ate, 0.01);
}
