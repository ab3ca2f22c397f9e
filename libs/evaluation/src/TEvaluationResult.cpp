#include "roislam/evaluation/TEvaluationResult.h"

#include <cstdio>

namespace roislam::evaluation
{
nlohmann::json toJson(const TEvaluationResult& result)
{
  const auto& a = result.ate;
  const auto& r = result.rpe;
  nlohmann::json j;
  j["ate"] = {
      {"rmse", a.rmse}, {"mean", a.mean}, {"median", a.median}, {"std", a.std},
      {"min", a.min},   {"max", a.max},   {"pairs", a.pairs},   {"mirrored_rmse", a.mirrored_rmse}};
  j["rpe"] = {
      {"trans_rmse", r.trans_rmse},
      {"trans_mean", r.trans_mean},
      {"trans_median", r.trans_median},
      {"trans_std", r.trans_std},
      {"trans_min", r.trans_min},
      {"trans_max", r.trans_max},
      {"rot_rmse_deg", r.rot_rmse_deg},
      {"rot_mean_deg", r.rot_mean_deg},
      {"rot_median_deg", r.rot_median_deg},
      {"rot_std_deg", r.rot_std_deg},
      {"rot_min_deg", r.rot_min_deg},
      {"rot_max_deg", r.rot_max_deg},
      {"pairs", r.pairs}};
  return j;
}

std::string mirrorWarning(const TAteResult& ate)
{
  if (!(ate.mirrored_rmse < 0.5 * ate.rmse))
    return {};
  char buf[320];
  std::snprintf(
      buf, sizeof(buf),
      "warning: the estimate fits the ground truth far better mirrored (ATE %.4f m against "
      "%.4f m): the two use opposite axis conventions; a ground truth of a y-up camera "
      "(ICL-NUIM) needs the camera given with fy < 0 (--camera icl)",
      ate.mirrored_rmse, ate.rmse);
  return buf;
}
}  // namespace roislam::evaluation
