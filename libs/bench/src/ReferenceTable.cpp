/* The reference section of report.md (ReferenceTable.h). */
#include "ReferenceTable.h"

#include <mrpt/system/string_utils.h>
#include <roislam/bench/CReportWriter.h>

#include <optional>
#include <string>

#include "ReportTables.h"

namespace roislam::bench::report
{
namespace
{
/** Our ms per frame is the whole run's wall time per frame, the
 *  reference's (ms_per_frame) its odometry alone. */
std::optional<double> msPerFrame(const TRunRecord& r)
{
  if (auto ms = r.number("ms_per_frame"))
    return ms;
  const auto frames = r.number("frames");
  if (!frames || *frames <= 0)
    return std::nullopt;
  return 1000 * durationOf(r) / *frames;
}

/** One row: the run's figures, or why it failed. */
void renderRow(
    std::ostream& md, const std::string& seq, const std::string& label, const TRunRecord& r)
{
  md << "| " << seq << " | " << label << " | ";
  if (!r.ok)
  {
    md << oneLine("FAILED: " + r.failureReason) << " | | | | |\n";
    return;
  }
  md << optNum(r.number("ate_rmse"), 4) << " | " << optNum(r.number("rpe_trans_rmse"), 4) << " | "
     << optNum(r.number("rpe_rot_rmse_deg"), 3) << " | " << optNum(msPerFrame(r), 1) << " | "
     << optNum(r.number("failed_frames"), 0) << " |\n";
}

/** Rows for our best and worst trajectory (lowest and highest ATE) of
 *  Tests 2-4 on `seq`; none when no run there succeeded with an ATE. */
void renderOursOn(
    std::ostream& md, const std::string& seq, const std::vector<const TRunRecord*>& all)
{
  const TRunRecord *best = nullptr, *worst = nullptr;
  for (const auto* r : all)
  {
    const auto ate = r->number("ate_rmse");
    if (r->run.test < 2 || r->run.sequence != seq || !r->ok || !ate)
      continue;
    if (!best || *ate < *best->number("ate_rmse"))
      best = r;
    if (!worst || *ate > *worst->number("ate_rmse"))
      worst = r;
  }
  const auto ours = [&](const char* which, const TRunRecord* r)
  {
    renderRow(
        md, seq,
        std::string("ours, ") + which + ": test " + std::to_string(r->run.test) + " " +
            CReportWriter::versionLabel(*r) + " " + mrpt::system::upperCase(r->run.feature),
        *r);
  };
  if (best)
    ours("best", best);
  if (worst && worst != best)
    ours("worst", worst);
}
}  // namespace

void renderReference(
    std::ostream& md, const std::vector<const TRunRecord*>& ref,
    const std::vector<const TRunRecord*>& all)
{
  md << "## Reference: OpenCV's cv::rgbd odometry, frame to frame\n\n"
        "cv-odometry runs OpenCV's RgbdOdometry (photometric), ICPOdometry (depth) and "
        "RgbdICPOdometry (both) with OpenCV's default parameters, each frame against the "
        "previous one, no keyframes, no loop closure, on the same frames with the same "
        "intrinsics (a distorted camera is undistorted first). A sequence where the "
        "reference fails too is hard; one where it beats us points to our system. Below each "
        "sequence's reference rows, our best and worst trajectory on it (Tests 2-4); our ms "
        "per frame is the whole run's wall time per frame, the reference's its odometry "
        "alone.\n\n"
        "| sequence | method | ATE RMSE (m) | RPE trans (m) | RPE rot (deg) | ms per frame | "
        "failed frames |\n|---|---|---|---|---|---|---|\n";
  for (const auto& s : distinct(ref, [](const TRunRecord& r) { return r.run.sequence; }))
  {
    for (const auto* r : ref)
      if (r->run.sequence == s)
        renderRow(
            md, s,
            "cv::rgbd " + r->run.mode.substr(3) + " (" +
                r->summary.value("opencv_class", std::string("reference")) + ")",
            *r);
    renderOursOn(md, s, all);
  }
  md << "\n";
}
}  // namespace roislam::bench::report
