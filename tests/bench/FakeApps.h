/* Fake roi-landmarks / roi-graphslam executables (shell scripts) for the bench
 * tests: they parse the contract's arguments and write a plausible
 * summary.json, so the runner, merge and report logic is tested without SLAM.
 * roi-graphslam fails (exit 1) in an ROI mode on a sequence whose path
 * contains "featureless" when the ini sets strict_roi = true, like the
 * dissertation's ROI versions. cv-odometry's ATE is 0.00k for --method number
 * k (rgbd 1, icp 2, rgbdicp 3). Every invocation appends a line to calls.log.
 */
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace roislam::bench::fake
{
inline void writeExecutable(const std::filesystem::path& p, const std::string& text)
{
  std::ofstream(p) << text;
  std::filesystem::permissions(
      p, std::filesystem::perms::owner_all | std::filesystem::perms::group_read |
             std::filesystem::perms::others_read);
}

/** Creates <dir>/roi-landmarks, <dir>/roi-graphslam, <dir>/cv-odometry and a config folder
 *  <dir>/config with the four ini files. */
inline void makeFakeApps(const std::string& dir)
{
  namespace fs = std::filesystem;
  fs::create_directories(fs::path(dir) / "config");
  const std::string common = R"(#!/bin/sh
out=""; mode=""; feature=""; ini=""; input=""; maxf=0
while [ $# -gt 0 ]; do
  case "$1" in
    --output-dir) out="$2"; shift;;
    --mode) mode="$2"; shift;;
    --feature) feature="$2"; shift;;
    --ini) ini="$2"; shift;;
    --input) input="$2"; shift;;
    --max-features) maxf="$2"; shift;;
  esac
  shift
done
echo "$0 $mode $feature $input" >> ")" +
                             dir + R"(/calls.log"
mkdir -p "$out"
case "$feature" in surf) k=1;; sift) k=2;; *) k=3;; esac
)";
  writeExecutable(fs::path(dir) / "roi-landmarks", common + R"(cat > "$out/summary.json" <<JSON
{"frames": 10, "frames_with_roi": 9, "landmarks": $((10 * k)), "recalls": 5,
 "false_positives": $k, "false_negatives": $((k + 1)), "precision": 0.$((9 - k)),
 "recall": 0.$((8 - k)), "matches_per_frame": 50, "false_matches_per_frame": 2,
 "duration_s": 1.5, "fps": 6.5}
JSON
)");
  writeExecutable(
      fs::path(dir) / "roi-graphslam",
      common + R"(if [ "$mode" != traditional ] && grep -q 'strict_roi = true' "$ini" && \
   echo "$input" | grep -q featureless; then
  echo "roi-graphslam: error: no ROI in frame 0" >&2; exit 1
fi
case "$mode" in traditional) m=1;; roi_small) m=2;; *) m=3;; esac
if [ -f "$input/groundtruth.txt" ]; then cp "$input/groundtruth.txt" "$out/trajectory.txt"; fi
cat > "$out/summary.json" <<JSON
{"frames": 10, "keyframes": 4, "loop_closures": 0, "tracked_frames": 10, "fallback_frames": 0,
 "lost_frames": 0, "wall_s": $m.5, "fps": $((10 * k)), "peak_rss_mb": 100,
 "ate_rmse": 0.0$m$k, "rpe_trans_rmse": 0.00$k, "rpe_rot_rmse_deg": 0.$m}
JSON
)");
  // cv-odometry: --method read before the common part consumes the arguments.
  const std::string shebang = "#!/bin/sh\n";
  writeExecutable(
      fs::path(dir) / "cv-odometry", shebang + R"(method=""; prev=""
for a in "$@"; do [ "$prev" = --method ] && method="$a"; prev="$a"; done
)" + common.substr(shebang.size()) +
                                         R"(case "$method" in rgbd) k=1;; icp) k=2;; *) k=3;; esac
cat > "$out/summary.json" <<JSON
{"frames": 10, "tracked_frames": 10, "failed_frames": 0, "ms_per_frame": $k.5,
 "opencv_class": "cv::rgbd::Fake$method", "wall_s": 0.5, "fps": 20,
 "ate_rmse": 0.00$k, "rpe_trans_rmse": 0.00$k, "rpe_rot_rmse_deg": 0.$k}
JSON
)");
  for (const char* f : {"roi_landmarks.ini", "traditional.ini", "roi_small.ini", "roi_big.ini"})
    std::ofstream(fs::path(dir) / "config" / f) << "[FrontEnd]\nfeature = surf\n";
}

/** A minimal TUM-layout sequence folder with a straight-line ground truth. */
inline std::string makeFakeSequence(const std::string& parent, const std::string& name)
{
  namespace fs = std::filesystem;
  const fs::path p = fs::path(parent) / name;
  fs::create_directories(p);
  std::ofstream(p / "rgb.txt") << "# fake\n";
  std::ofstream gt(p / "groundtruth.txt");
  for (int i = 0; i < 20; ++i)
    gt << 100 + 0.1 * i << " " << 0.05 * i << " " << 0.02 * i * i / 20.0 << " 1.0 0 0 0 1\n";
  return p.string();
}
}  // namespace roislam::bench::fake
