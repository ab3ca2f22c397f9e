#include "roislam/evaluation/CTrajectoryEvaluator.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniRead.h>
#include <roislam/geometry/RigidAlignment.h>
#include <roislam/io/StampAssociation.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>

namespace roislam::evaluation
{
namespace
{
struct TStats
{
  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0;
};

/** numpy conventions: rmse = sqrt(dot(e,e)/n), population std, median of an
 *  even count = mean of the two middle values. */
TStats computeStats(std::vector<double> e)
{
  TStats s;
  const double n = static_cast<double>(e.size());
  double sum = 0, sumSq = 0;
  for (double v : e)
  {
    sum += v;
    sumSq += v * v;
  }
  s.rmse = std::sqrt(sumSq / n);
  s.mean = sum / n;
  double var = 0;
  for (double v : e)
    var += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(var / n);
  std::sort(e.begin(), e.end());
  s.min = e.front();
  s.max = e.back();
  const std::size_t m = e.size() / 2;
  s.median = (e.size() % 2 == 1) ? e[m] : 0.5 * (e[m - 1] + e[m]);
  return s;
}

/** evaluate_rpe.py's find_closest_index(): a bisection that remembers the
 *  first visited element with the strictly smallest |L[k] - t|, returning at
 *  once on an exact hit. L sorted ascending and non-empty. Reproduced step by
 *  step because its choice between two equidistant neighbours depends on the
 *  visiting order. */
std::size_t findClosestIndex(const std::vector<double>& L, double t)
{
  std::size_t begin = 0, end = L.size(), best = 0;
  double difference = std::abs(L[0] - t);
  while (begin < end)
  {
    const std::size_t middle = (begin + end) / 2;
    if (std::abs(L[middle] - t) < difference)
    {
      difference = std::abs(L[middle] - t);
      best = middle;
    }
    if (t == L[middle])
      return middle;
    if (L[middle] > t)
      end = middle;
    else
      begin = middle + 1;
  }
  return best;
}

/** Sorted by stamp; of equal stamps the last one wins (the scripts' dicts). */
io::TTrajectory asStampDict(const io::TTrajectory& in)
{
  io::TTrajectory t = in;
  std::stable_sort(
      t.begin(), t.end(), [](const auto& a, const auto& b) { return a.timestamp < b.timestamp; });
  io::TTrajectory out;
  out.reserve(t.size());
  for (auto& p : t)
  {
    if (!out.empty() && out.back().timestamp == p.timestamp)
      out.back() = std::move(p);
    else
      out.push_back(std::move(p));
  }
  return out;
}

std::vector<double> stampsOf(const io::TTrajectory& t)
{
  std::vector<double> s;
  s.reserve(t.size());
  for (const auto& p : t)
    s.push_back(p.timestamp);
  return s;
}

std::string num(double v)
{
  std::ostringstream ss;
  ss << v;
  return ss.str();
}
}  // namespace

std::string toString(CTrajectoryEvaluator::TDeltaUnit unit)
{
  return unit == CTrajectoryEvaluator::TDeltaUnit::Frames ? "f" : "s";
}

CTrajectoryEvaluator::TDeltaUnit deltaUnitFromString(const std::string& text)
{
  if (text == "s")
    return CTrajectoryEvaluator::TDeltaUnit::Seconds;
  if (text == "f")
    return CTrajectoryEvaluator::TDeltaUnit::Frames;
  throw std::invalid_argument("delta unit must be 's' or 'f', not '" + text + "'");
}

void CTrajectoryEvaluator::TOptions::validate(const std::string& section) const
{
  if (!(std::isfinite(max_difference) && max_difference > 0))
    throw std::invalid_argument(
        "[" + section + "] max_difference: must be > 0 s, got " + num(max_difference));
  if (!std::isfinite(offset))
    throw std::invalid_argument("[" + section + "] offset: must be finite");
  if (!(std::isfinite(delta) && delta > 0))
    throw std::invalid_argument("[" + section + "] delta: must be > 0, got " + num(delta));
}

void CTrajectoryEvaluator::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
  max_difference = common::readDouble(cfg, section, "max_difference", max_difference);
  offset = common::readDouble(cfg, section, "offset", offset);
  delta = common::readDouble(cfg, section, "delta", delta);
  const std::string unit = cfg.read_string(section, "delta_unit", toString(delta_unit), false);
  try
  {
    delta_unit = deltaUnitFromString(unit);
  }
  catch (const std::invalid_argument&)
  {
    throw std::invalid_argument(
        "[" + section + "] delta_unit: must be 's' or 'f', not '" + unit + "'");
  }
  validate(section);
}

void CTrajectoryEvaluator::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& cfg, const std::string& section) const
{
  cfg.write(section, "max_difference", max_difference);
  cfg.write(section, "offset", offset);
  cfg.write(section, "delta", delta);
  cfg.write(section, "delta_unit", toString(delta_unit));
}

CTrajectoryEvaluator::CTrajectoryEvaluator() : CTrajectoryEvaluator(TOptions()) {}

CTrajectoryEvaluator::CTrajectoryEvaluator(const TOptions& options) : m_options(options)
{
  m_options.validate();
}

namespace
{
/** Both trajectories as stamp dictionaries (sorted, one pose per stamp), with their stamps. */
struct TStampedPair
{
  io::TTrajectory gt, est;
  std::vector<double> gtStamps, estStamps;
};

/** associate.py + evaluate_ate.py: result.ate and result.aligned. */
void evaluateAte(
    const TStampedPair& p, const CTrajectoryEvaluator::TOptions& o, TEvaluationResult& result)
{
  // associate.py semantics (exact |dt| < max_difference test, greedy).
  const auto matches = io::associateStamps(p.gtStamps, p.estStamps, o.max_difference, o.offset);
  const std::string window =
      "max_difference " + num(o.max_difference) + " s, offset " + num(o.offset) + " s";
  if (matches.empty())
    throw std::runtime_error("no estimated stamp has a ground-truth stamp within " + window);
  if (matches.size() < 3)
    throw std::runtime_error(
        "only " + std::to_string(matches.size()) +
        " estimated stamps associate with ground truth within " + window + " (need 3)");

  const std::size_t n = matches.size();
  Eigen::Matrix3Xd model(3, n), data(3, n);  // model = estimate, data = ground truth
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto& g = p.gt[matches[k].first].pose;
    const auto& e = p.est[matches[k].second].pose;
    data.col(k) << g.x(), g.y(), g.z();
    model.col(k) << e.x(), e.y(), e.z();
  }
  // align(): the least-squares rotation and translation (no scale) by SVD,
  // which is what geometry::alignRigid (Eigen::umeyama) computes.
  const geometry::TRigid T = geometry::alignRigid(data, model);
  std::vector<double> ateErrors(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    ateErrors[k] = (T * model.col(k) - data.col(k)).norm();
    result.ate.samples.push_back({p.estStamps[matches[k].second], ateErrors[k]});
  }
  std::sort(
      result.ate.samples.begin(), result.ate.samples.end(),
      [](const auto& a, const auto& b) { return a.timestamp < b.timestamp; });
  const TStats ate = computeStats(ateErrors);
  result.ate.rmse = ate.rmse;
  result.ate.mean = ate.mean;
  result.ate.median = ate.median;
  result.ate.std = ate.std;
  result.ate.min = ate.min;
  result.ate.max = ate.max;
  result.ate.pairs = n;
  result.ate.alignment = T.toPose();
  // Every reflection is diag(1, -1, 1) times a rotation, so mirroring y and
  // aligning rigidly finds the best improper alignment.
  Eigen::Matrix3Xd mirrored = model;
  mirrored.row(1) *= -1;
  const geometry::TRigid M = geometry::alignRigid(data, mirrored);
  double sq = 0;
  for (std::size_t k = 0; k < n; ++k)
    sq += (M * mirrored.col(k) - data.col(k)).squaredNorm();
  result.ate.mirrored_rmse = std::sqrt(sq / static_cast<double>(n));
  result.aligned.reserve(p.est.size());
  for (const auto& e : p.est)
    result.aligned.push_back(io::TPoseStamped{e.timestamp, result.ate.alignment + e.pose});
}

/** evaluate_rpe.py's check that the stamps overlap: throws when fewer than
 *  two estimated stamps survive the round trip to the ground truth. */
void checkRpeOverlap(const TStampedPair& p, double offset)
{
  std::set<std::size_t> roundTrip;
  for (double te : p.estStamps)
  {
    const double tg = p.gtStamps[findClosestIndex(p.gtStamps, te + offset)];
    roundTrip.insert(findClosestIndex(p.estStamps, tg - offset));
  }
  if (roundTrip.size() < 2)
    throw std::runtime_error(
        "too few overlapping stamps between the estimate and the ground truth for RPE");
}

/** The RPE statistics of translation [m] and rotation [rad] errors. */
void fillRpeStats(
    const std::vector<double>& transErrors, const std::vector<double>& rotErrors, TRpeResult& rpe)
{
  const TStats tr = computeStats(transErrors);
  const TStats ro = computeStats(rotErrors);
  const double deg = 180.0 / M_PI;
  rpe.pairs = transErrors.size();
  rpe.trans_rmse = tr.rmse;
  rpe.trans_mean = tr.mean;
  rpe.trans_median = tr.median;
  rpe.trans_std = tr.std;
  rpe.trans_min = tr.min;
  rpe.trans_max = tr.max;
  rpe.rot_rmse_deg = ro.rmse * deg;
  rpe.rot_mean_deg = ro.mean * deg;
  rpe.rot_median_deg = ro.median * deg;
  rpe.rot_std_deg = ro.std * deg;
  rpe.rot_min_deg = ro.min * deg;
  rpe.rot_max_deg = ro.max * deg;
}

/** evaluate_rpe.py --fixed_delta: rpe. */
void evaluateRpe(const TStampedPair& p, const CTrajectoryEvaluator::TOptions& o, TRpeResult& rpe)
{
  checkRpeOverlap(p, o.offset);
  const auto& gtStamps = p.gtStamps;
  const auto& estStamps = p.estStamps;
  std::vector<double> index(estStamps.size());
  if (o.delta_unit == CTrajectoryEvaluator::TDeltaUnit::Seconds)
    index = estStamps;
  else
    std::iota(index.begin(), index.end(), 0.0);

  std::vector<double> gtIntervals;
  for (std::size_t k = 1; k < gtStamps.size(); ++k)
    gtIntervals.push_back(gtStamps[k] - gtStamps[k - 1]);
  // A single ground-truth pose cannot get here (ATE needs 3 associations).
  const double gtMaxTimeDifference = 2 * computeStats(gtIntervals).median;

  std::vector<double> transErrors, rotErrors;
  const std::size_t last = p.est.size() - 1;
  for (std::size_t i = 0; i < p.est.size(); ++i)
  {
    const std::size_t j = findClosestIndex(index, index[i] + o.delta);
    if (j == last)
      continue;
    const std::size_t g0 = findClosestIndex(gtStamps, estStamps[i] + o.offset);
    const std::size_t g1 = findClosestIndex(gtStamps, estStamps[j] + o.offset);
    if (std::abs(gtStamps[g0] - (estStamps[i] + o.offset)) > gtMaxTimeDifference ||
        std::abs(gtStamps[g1] - (estStamps[j] + o.offset)) > gtMaxTimeDifference)
      continue;
    // (E_i^-1 E_j)(G_i^-1 G_j)^-1; in MRPT notation a - b = b^-1 (+) a.
    const mrpt::poses::CPose3D relEst = p.est[j].pose - p.est[i].pose;
    const mrpt::poses::CPose3D relGt = p.gt[g1].pose - p.gt[g0].pose;
    mrpt::poses::CPose3D relGtInv = relGt;
    relGtInv.inverse();
    const mrpt::poses::CPose3D error = relEst + relGtInv;
    transErrors.push_back(error.translation().norm());
    const auto Rm = error.getRotationMatrix();
    const double c = std::min(1.0, std::max(-1.0, (Rm(0, 0) + Rm(1, 1) + Rm(2, 2) - 1) / 2));
    rotErrors.push_back(std::acos(c));
    rpe.samples.push_back({estStamps[i], transErrors.back(), rotErrors.back() * 180.0 / M_PI});
  }
  if (transErrors.size() < 2)
    throw std::runtime_error(
        "only " + std::to_string(transErrors.size()) +
        " RPE pose pairs (need 2): the estimate is shorter than delta = " + num(o.delta) + " " +
        toString(o.delta_unit) + " or lacks nearby ground truth");
  fillRpeStats(transErrors, rotErrors, rpe);
}
}  // namespace

TEvaluationResult CTrajectoryEvaluator::evaluate(
    const io::TTrajectory& gtIn, const io::TTrajectory& estIn) const
{
  if (gtIn.empty())
    throw std::runtime_error("the ground-truth trajectory is empty");
  if (estIn.empty())
    throw std::runtime_error("the estimated trajectory is empty");
  TStampedPair p;
  p.gt = asStampDict(gtIn);
  p.est = asStampDict(estIn);
  p.gtStamps = stampsOf(p.gt);
  p.estStamps = stampsOf(p.est);
  TEvaluationResult result;
  evaluateAte(p, m_options, result);
  evaluateRpe(p, m_options, result.rpe);
  return result;
}
}  // namespace roislam::evaluation
