#include "roislam/kfslam/CKfSlamFilter.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/vector_loadsave.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/serialization/CSerializable.h>
#include <mrpt/slam/CRangeBearingKFSLAM.h>
#include <mrpt/system/string_utils.h>
#include <roislam/common/ErrorText.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>

namespace roislam::kfslam
{
namespace
{
void recordStep(
    const mrpt::slam::CRangeBearingKFSLAM& filter, const mrpt::obs::CSensoryFrame& sf,
    TKfSlamRun& run)
{
  const auto obs = sf.getObservationByClass<mrpt::obs::CObservationBearingRange>();
  run.robotPath.emplace_back(mrpt::poses::CPose3D(filter.getCurrentRobotPoseMean()));
  run.stamps.push_back(obs ? mrpt::Clock::toDouble(obs->timestamp) : 0.0);
  run.measurements.push_back(obs ? obs->sensedData.size() : 0);
  if (!run.firstLandmarkStep && filter.getNumberOfLandmarksInTheMap() > 0)
    run.firstLandmarkStep = run.robotPath.size() - 1;
}

/** The next object of a rawlog of (action, sensory frame) pairs, of class T;
 *  nullptr at the end of the file when endAllowed. MRPT's own
 *  CRawlog::readActionObservationPair prints and swallows read errors, so a
 *  corrupt file would look like a short one. */
template <typename T>
typename T::Ptr readObject(
    mrpt::serialization::CArchive& ar, const std::string& file, std::size_t entry, bool endAllowed)
{
  mrpt::serialization::CSerializable::Ptr obj;
  try
  {
    obj = ar.ReadObject();
  }
  catch (const mrpt::serialization::CExceptionEOF&)
  {
    if (endAllowed)
      return nullptr;
    throw std::runtime_error(file + ": ends inside entry " + std::to_string(entry));
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(
        file + ": corrupt at entry " + std::to_string(entry) + ": " + common::firstLine(e.what()));
  }
  auto typed = std::dynamic_pointer_cast<T>(obj);
  if (!typed)
    throw std::runtime_error(
        file + ": entry " + std::to_string(entry) + " is a " +
        (obj ? std::string(obj->GetRuntimeClass()->className) : std::string("null")) +
        ", expected " + T::GetRuntimeClassIdStatic().className +
        " (a kf-slam rawlog of action / sensory-frame pairs)");
  return typed;
}

std::map<int64_t, mrpt::math::TPoint3D> finalMap(const mrpt::slam::CRangeBearingKFSLAM& filter)
{
  mrpt::poses::CPose3DQuatPDFGaussian pose;
  std::vector<mrpt::math::TPoint3D> points;
  std::map<unsigned int, mrpt::maps::CLandmark::TLandmarkID> ids;
  mrpt::math::CVectorDouble state;
  mrpt::math::CMatrixDouble cov;
  filter.getCurrentState(pose, points, ids, state, cov);
  std::map<int64_t, mrpt::math::TPoint3D> map;
  for (const auto& [index, id] : ids)
    map[id] = points.at(index);
  return map;
}
}  // namespace

CKfSlamFilter::CKfSlamFilter(const std::string& iniFile) : m_file(iniFile)
{
  if (!std::filesystem::is_regular_file(iniFile))
    throw std::runtime_error("ini " + iniFile + ": cannot open");
  m_ini = mrpt::io::file_get_contents(iniFile);
  const mrpt::config::CConfigFileMemory cfg(m_ini);
  const std::string& label = iniFile;
  const std::string impl = mrpt::system::trim(
      cfg.read_string("MappingApplication", "kf_implementation", "CRangeBearingKFSLAM"));
  if (impl != "CRangeBearingKFSLAM")
    throw std::invalid_argument(
        "ini " + label + ": [MappingApplication] kf_implementation: '" + impl +
        "': roi-landmarks runs the 6-DoF CRangeBearingKFSLAM (3-D landmarks)");
  // Load once here so that a bad option fails before any frame is processed.
  mrpt::slam::CRangeBearingKFSLAM probe;
  try
  {
    probe.loadOptions(cfg);
  }
  catch (const std::exception& e)
  {
    throw std::invalid_argument("ini " + label + ": " + common::firstLine(e.what()));
  }
}

TKfSlamRun CKfSlamFilter::run(const std::string& rawlog) const
{
  if (!std::filesystem::is_regular_file(rawlog))
    throw std::runtime_error(rawlog + ": cannot open");
  mrpt::config::CConfigFileMemory cfg(m_ini);
  mrpt::slam::CRangeBearingKFSLAM filter;
  filter.loadOptions(cfg);
  // kf-slam logs every step at INFO; keep warnings only unless the ini asks.
  if (!cfg.keyExists("RangeBearingKFSLAM_KalmanFilter", "verbosity_level"))
    filter.setMinLoggingLevel(mrpt::system::LVL_WARN);
  mrpt::io::CFileGZInputStream in;
  if (!in.open(rawlog))
    throw std::runtime_error(rawlog + ": cannot open");
  auto ar = mrpt::serialization::archiveFrom(in);
  TKfSlamRun run;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t entry = 0;; entry += 2)
  {
    auto action = readObject<mrpt::obs::CActionCollection>(ar, rawlog, entry, true);
    if (!action)
      break;
    auto sf = readObject<mrpt::obs::CSensoryFrame>(ar, rawlog, entry + 1, false);
    try
    {
      filter.processActionObservation(action, sf);
    }
    catch (const std::exception& e)
    {
      throw std::runtime_error(
          rawlog + ": EKF failed at step " + std::to_string(run.robotPath.size()) + ": " +
          common::firstLine(e.what()));
    }
    recordStep(filter, *sf, run);
  }
  if (run.robotPath.empty())
    throw std::runtime_error(rawlog + ": no (CActionCollection, CSensoryFrame) pairs");
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  run.landmarks = finalMap(filter);
  return run;
}
}  // namespace roislam::kfslam
