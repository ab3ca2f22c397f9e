// Developer probe (not a test): odometry over a sequence with an ini file.
#include <mrpt/config/CConfigFile.h>

#include <iostream>

#include "OdometryRun.h"

int main(int argc, char** argv)
{
  using namespace roislam::frontend;
  CRgbdOdometry::TOptions o;
  if (argc > 2)
  {
    mrpt::config::CConfigFile cfg(argv[2]);
    o.loadFromConfigFile(cfg, "FrontEnd");
  }
  const auto s = testing::runOdometry(argv[1], o, argc > 3 ? std::stoul(argv[3]) : 0);
  TStageTimes m;
  double nm = 0, ni = 0, nf = 0;
  for (const auto& r : s.results)
  {
    m.roi_ms += r.times.roi_ms;
    m.extract_ms += r.times.extract_ms;
    m.lift_ms += r.times.lift_ms;
    m.match_ms += r.times.match_ms;
    m.ransac_ms += r.times.ransac_ms;
    m.icp_ms += r.times.icp_ms;
    m.keyframe_ms += r.times.keyframe_ms;
    m.total_ms += r.times.total_ms;
    nm += r.matches;
    ni += r.inliers;
    nf += r.trackingFeatures;
  }
  const double n = static_cast<double>(s.results.size());
  std::cout << "ATE " << (s.ate ? *s.ate : -1) << " frames " << n << " kf " << s.keyframes
            << " fps " << n / s.wallSeconds << " proc_ms " << m.total_ms / n << " [roi "
            << m.roi_ms / n << " ext " << m.extract_ms / n << " lift " << m.lift_ms / n << " match "
            << m.match_ms / n << " ransac " << m.ransac_ms / n << " icp " << m.icp_ms / n << " kf "
            << m.keyframe_ms / n << "] feats " << nf / n << " matches " << nm / n << " inl "
            << ni / n << " | feat " << s.stats.features << " roi " << s.stats.roiFeatures << " fb "
            << s.stats.fullImageFallback << " icp " << s.stats.depthIcp << " cv "
            << s.stats.constantVelocity << " lost " << s.stats.lost << " noroi " << s.stats.noRoi
            << "\n";
}
