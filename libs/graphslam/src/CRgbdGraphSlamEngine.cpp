#include <fcntl.h>
#include <mrpt/core/exceptions.h>
#include <mrpt/system/filesystem.h>
#include <mrpt/system/string_utils.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/graphslam/CRgbdGraphSlamEngine.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <mutex>
#include <stdexcept>

namespace roislam::graphslam
{
namespace
{
/** For its lifetime: stdin reads from /dev/null, stdout writes to it. */
class CQuietConsole
{
 public:
  CQuietConsole()
  {
    std::cout.flush();
    std::fflush(stdout);
    m_in = dup(0);
    m_out = dup(1);
    const int null = open("/dev/null", O_RDWR);
    if (null >= 0)
    {
      dup2(null, 0);
      dup2(null, 1);
      close(null);
    }
  }
  ~CQuietConsole()
  {
    std::cout.flush();
    std::fflush(stdout);
    if (m_in >= 0)
      dup2(m_in, 0), close(m_in);
    if (m_out >= 0)
      dup2(m_out, 1), close(m_out);
  }
  CQuietConsole(const CQuietConsole&) = delete;
  CQuietConsole& operator=(const CQuietConsole&) = delete;

 private:
  int m_in = -1, m_out = -1;
};

/** Rethrows the exception being handled with its own message: MRPT_END in
 *  the engine wraps what our deciders throw into a many-line text with a
 *  call stack (and misreads a "[Section]" in the message as a location). */
[[noreturn]] void rethrowOwnMessage()
{
  try
  {
    throw;
  }
  catch (const mrpt::ExceptionWithCallBackBase& e)
  {
    throw std::runtime_error(e.originalWhat.substr(0, e.originalWhat.find('\n')));
  }
}
}  // namespace

std::unique_ptr<CRgbdGraphSlamEngine> CRgbdGraphSlamEngine::create(
    const std::string& iniFile, const TSlamDeciders& deciders)
{
  if (!iniFile.empty() && mrpt::system::fileExists(iniFile))
  {
    // With this format the constructor points CImage's global image folder
    // at "<rawlog>_Images/" (for its RGBD-TUM reader, 2-D only in 2.5), which
    // would hide the external images of our rawlogs.
    // Every line checked (file:line errors) before MRPT's engine and its
    // deciders read the same file with MRPT's lenient parser.
    const common::CStrictIniFile cfg(iniFile);
    if (mrpt::system::strCmpI(
            cfg.read_string("GeneralConfiguration", "ground_truth_file_format", "NavSimul"),
            "rgbd_tum"))
      throw std::invalid_argument(
          "ini " + iniFile +
          ": [GeneralConfiguration] ground_truth_file_format: rgbd_tum is read by MRPT 2.5 for "
          "2-D graphs only (give the TUM ground truth with -g)");
  }
  // The constructor's key-press pause (see the header): no console for it.
  const CQuietConsole quiet;
  try
  {
    return std::unique_ptr<CRgbdGraphSlamEngine>(new CRgbdGraphSlamEngine(iniFile, deciders));
  }
  catch (...)
  {
    rethrowOwnMessage();
  }
}

// No rawlog name (it only serves MRPT's RGBD-TUM image-folder heuristics:
// io::CFrameSource reads the data) and no ground truth (MRPT 2.5 cannot read
// one for 3-D graphs: CSlamRunner evaluates against the TUM file instead).
CRgbdGraphSlamEngine::CRgbdGraphSlamEngine(
    const std::string& iniFile, const TSlamDeciders& deciders)
    : CGraphSlamEngine<TGraph>(
          iniFile, "", "", nullptr, deciders.node.get(), deciders.edge.get(),
          deciders.optimizer.get())
{
}

CRgbdGraphSlamEngine::~CRgbdGraphSlamEngine()
{
  // Its table goes to the report (getDescriptiveReport()), not the console.
  this->m_time_logger.clear(true);
}

bool CRgbdGraphSlamEngine::step(mrpt::obs::CObservation::Ptr observation)
{
  try
  {
    const bool go = this->execGraphSlamStep(observation, m_entry);
    ++m_entry;
    return go;
  }
  catch (...)
  {
    rethrowOwnMessage();
  }
}

std::string CRgbdGraphSlamEngine::descriptiveReport() const
{
  std::string report;
  this->getDescriptiveReport(&report);
  return report;
}

double CRgbdGraphSlamEngine::lastSectionMs(const std::string& section) const
{
  return 1e3 * this->m_time_logger.getLastTime(section);
}

double CRgbdGraphSlamEngine::lastBackendMs() const
{
  return 1e3 * (this->m_time_logger.getLastTime("edge_registrar") +
                this->m_time_logger.getLastTime("optimizer"));
}

bool CRgbdGraphSlamEngine::_execGraphSlamStep(
    mrpt::obs::CActionCollection::Ptr& action, mrpt::obs::CSensoryFrame::Ptr& observations,
    mrpt::obs::CObservation::Ptr& observation, size_t& rawlog_entry)
{
  m_posesSaved = false;
  const bool go =
      CGraphSlamEngine<TGraph>::_execGraphSlamStep(action, observations, observation, rawlog_entry);
  if (m_posesSaved)
  {
    // MRPT 2.5 replaced every pose by its spanning-tree estimate after the
    // optimiser ran (execDijkstraNodesEstimation()): put the optimiser's
    // poses back, for the next step's deciders and for the caller.
    std::lock_guard<std::mutex> lock(this->m_graph_section);
    this->m_graph.nodes = std::move(m_optimizedPoses);
    m_optimizedPoses.clear();
    m_posesSaved = false;
  }
  return go;
}

void CRgbdGraphSlamEngine::monitorNodeRegistration(bool registered, std::string class_name)
{
  CGraphSlamEngine<TGraph>::monitorNodeRegistration(registered, class_name);
  // The engine calls this after each of the node decider, the edge decider
  // and the optimiser; with a node registered, the spanning-tree reset
  // follows the optimiser's call.
  if (registered && class_name == "GraphSlamOptimizer")
  {
    std::lock_guard<std::mutex> lock(this->m_graph_section);
    m_optimizedPoses = this->m_graph.nodes;
    m_posesSaved = true;
  }
}
}  // namespace roislam::graphslam
