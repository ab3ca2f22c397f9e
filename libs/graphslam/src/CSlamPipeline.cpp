#include "roislam/graphslam/CSlamPipeline.h"

#include <roislam/graphslam/CKeyframeGSO.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>
#include <roislam/io/ObservationConversion.h>

#include <stdexcept>

namespace roislam::graphslam
{
CSlamPipeline::CSlamPipeline(
    const CSlamContext::TConfig& config, std::unique_ptr<io::CFrameSource> source,
    const std::string& engineIni)
    : CSlamPipeline(
          CRoislamOptionsChecker().createDeciders(TSlamDeciders::TNames(), &config), engineIni,
          std::move(source), {})
{
}

CSlamPipeline::CSlamPipeline(
    const TSlamDeciders::TNames& names, const std::string& iniFile,
    std::unique_ptr<io::CFrameSource> source,
    const std::function<void(CSlamContext::TConfig&)>& adjust)
    : CSlamPipeline(
          CRoislamOptionsChecker().createDeciders(names), iniFile, std::move(source), adjust)
{
}

CSlamPipeline::CSlamPipeline(
    TSlamDeciders deciders, const std::string& engineIni, std::unique_ptr<io::CFrameSource> source,
    const std::function<void(CSlamContext::TConfig&)>& adjust)
    : m_source(std::move(source)), m_deciders(std::move(deciders))
{
  if (!m_source)
    throw std::invalid_argument("CSlamPipeline: no frame source");
  if (!m_deciders.ourNode())
    throw std::invalid_argument(
        "CSlamPipeline: the node registration decider must be CKeyframeNRD");
  // The engine calls the deciders' loadParams(): our context is configured
  // when it returns.
  m_engine = CRgbdGraphSlamEngine::create(engineIni, m_deciders);
  if (adjust)
  {
    // Before the prefetch thread holds on to the front end configure() replaces.
    CSlamContext::TConfig config = m_deciders.context->config();
    adjust(config);
    m_deciders.context->configure(config);
  }
  m_records.reserve(m_source->size());
  // The prefetch thread prepares frames with a front end of its own, built
  // from the same options (prepare() reads only them and the ROI detector
  // they make): nothing it touches is reachable from step(), which runs
  // process() on the tracking front end and corrects its keyframes.
  m_preparer =
      std::make_unique<const frontend::CRgbdOdometry>(m_deciders.context->config().frontEnd);
  m_prefetch = std::make_unique<io::CFramePrefetcher<TAhead>>(
      *m_source, 1,
      [&odo = *m_preparer](const io::TRGBDFrame& f) {
        return TAhead{odo.prepare(f), io::frameToObservation(f)};
      });
}

CSlamPipeline::~CSlamPipeline()
{
  // The prefetch thread uses the source and the context: stop it first.
  m_prefetch.reset();
  // The engine points to the deciders.
  m_engine.reset();
}

bool CSlamPipeline::step()
{
  auto item = m_prefetch->next();
  if (!item)
    return false;
  TAhead& ahead = item->prepared;
  const std::size_t recorded = context().framesRecorded();
  // The observer's copy of the frame (cv::Mat headers): the prepared frame
  // moves into the node decider.
  const io::TRGBDFrame frame = m_observer ? ahead.prepared.frame : io::TRGBDFrame();
  const auto optimizationsBefore = optimizations();
  // The engine steps on the observation; our node decider tracks the frame
  // prepared ahead for it, and hands the result on (CSlamContext::lastFrame).
  m_deciders.ourNode()->prepareAhead(ahead.observation.get(), std::move(ahead.prepared));
  m_engine->step(ahead.observation);
  if (context().framesRecorded() != recorded + 1)
    throw std::logic_error("CSlamPipeline: the node decider did not track the frame");
  TFrameRecord record{*context().lastFrame()};
  record.edgeMs = m_engine->lastSectionMs("edge_registrar");
  record.optimizerMs = m_engine->lastSectionMs("optimizer");
  record.backendMs = record.edgeMs + record.optimizerMs;
  if (record.result.isNewKeyframe)
    record.spanningTreeMs = m_engine->lastSectionMs("dijkstra_nodes_estimation");
  m_records.push_back(std::move(record));
  if (m_observer)
  {
    if (optimizations() != optimizationsBefore)
      m_observer->onOptimized(graph(), context());
    m_observer->onFrame(m_records.back().result, frame, context());
  }
  return true;
}

void CSlamPipeline::setObserver(CSlamObserver* observer)
{
  m_observer = observer;
  if (m_observer)
    m_observer->onStart(*m_source, context());
}

std::optional<TOptimizationReport> CSlamPipeline::finish()
{
  if (auto* gso = m_deciders.ourOptimizer())
  {
    const auto report = gso->finish();
    if (m_observer)
      m_observer->onOptimized(graph(), context());
    return report;
  }
  return std::nullopt;
}

std::optional<std::size_t> CSlamPipeline::optimizations() const
{
  if (const auto* gso = m_deciders.ourOptimizer())
    return gso->optimizations();
  return std::nullopt;
}

std::optional<std::size_t> CSlamPipeline::windowedOptimizations() const
{
  if (const auto* gso = m_deciders.ourOptimizer())
    return gso->windowedOptimizations();
  return std::nullopt;
}

std::string CSlamPipeline::report() const
{
  std::string out = m_engine->descriptiveReport(), part;
  const mrpt::graphslam::CRegistrationDeciderOrOptimizer<TGraph>* parts[] = {
      m_deciders.node.get(), m_deciders.edge.get(), m_deciders.optimizer.get()};
  for (const auto* p : parts)
  {
    part.clear();
    p->getDescriptiveReport(&part);
    out += "\n" + part;
  }
  return out;
}

mrpt::poses::CPose3D CSlamPipeline::keyframePose(std::size_t id) const
{
  const auto& g = graph();
  const auto it = g.nodes.find(id);
  return it != g.nodes.end() ? it->second : context().odometry().keyframe(id).pose;
}

io::TTrajectory CSlamPipeline::trajectory() const
{
  io::TTrajectory estimate;
  for (const auto& r : m_records)
  {
    const auto& fr = r.result;
    if (!fr.pose)
      continue;
    io::TPoseStamped p;
    p.timestamp = fr.timestamp;
    p.pose = fr.isNewKeyframe ? keyframePose(fr.newKeyframeId)
                              : keyframePose(fr.referenceKeyframe) + fr.relativePose;
    estimate.push_back(p);
  }
  return estimate;
}
}  // namespace roislam::graphslam
