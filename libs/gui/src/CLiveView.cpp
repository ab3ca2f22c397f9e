#include "roislam/gui/CLiveView.h"

#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/common/IniRead.h>
#include <roislam/io/TumTrajectory.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "LiveViewImpl.h"

namespace roislam::gui
{
using detail::secondsSince;
using detail::TUpdate;

namespace
{
constexpr const char* kSection = "LiveView";
}  // namespace

// ---- options ----------------------------------------------------------------

void CLiveView::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  refresh_hz = common::readDouble(c, s, "refresh_hz", refresh_hz);
  max_cpu_share = common::readDouble(c, s, "max_cpu_share", max_cpu_share);
  width = common::readInt(c, s, "width", width);
  height = common::readInt(c, s, "height", height);
  map_points_per_keyframe =
      common::readInt(c, s, "map_points_per_keyframe", map_points_per_keyframe);
  point_size_px = common::readDouble(c, s, "point_size_px", point_size_px);
  flash_s = common::readDouble(c, s, "flash_s", flash_s);
  max_depth_m = common::readDouble(c, s, "max_depth_m", max_depth_m);
  follow = common::readBool(c, s, "follow", follow);
  validate();
}

void CLiveView::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "refresh_hz", refresh_hz);
  c.write(s, "max_cpu_share", max_cpu_share);
  c.write(s, "width", width);
  c.write(s, "height", height);
  c.write(s, "map_points_per_keyframe", map_points_per_keyframe);
  c.write(s, "point_size_px", point_size_px);
  c.write(s, "flash_s", flash_s);
  c.write(s, "max_depth_m", max_depth_m);
  c.write(s, "follow", follow);
}

void CLiveView::TOptions::validate() const
{
  common::require(
      refresh_hz >= 0.5 && refresh_hz <= 60, kSection, "refresh_hz", refresh_hz, "in [0.5, 60]");
  common::require(
      max_cpu_share > 0 && max_cpu_share <= 1, kSection, "max_cpu_share", max_cpu_share,
      "in (0, 1]");
  common::require(width >= 320, kSection, "width", width, ">= 320");
  common::require(height >= 240, kSection, "height", height, ">= 240");
  common::require(
      map_points_per_keyframe >= 1, kSection, "map_points_per_keyframe", map_points_per_keyframe,
      ">= 1");
  common::require(point_size_px > 0, kSection, "point_size_px", point_size_px, "> 0");
  common::require(flash_s >= 0, kSection, "flash_s", flash_s, ">= 0");
  common::require(max_depth_m > 0, kSection, "max_depth_m", max_depth_m, "> 0");
}

CLiveView::TOptions CLiveView::loadOptions(const std::string& iniFile)
{
  TOptions o;
  if (iniFile.empty())
    return o;
  const common::CStrictIniFile cfg(iniFile);  // syntax checked: file:line errors
  common::checkIniKeys(cfg, kSection, common::knownIniKeys(o, kSection), iniFile);
  o.loadFromConfigFile(cfg, kSection);
  return o;
}

// ---- CLiveView ----------------------------------------------------------------

CLiveView::CLiveView(const TOptions& options, TSession session)
    : m_impl(std::make_unique<TImpl>(options, std::move(session)))
{
}

CLiveView::~CLiveView() = default;

void CLiveView::onOutputFolder(const std::string& dir)
{
  std::lock_guard<std::mutex> lk(m_impl->mutex);
  m_impl->session.screenshotDir = dir;
}

void CLiveView::onStart(const io::CFrameSource& source, const graphslam::CSlamContext& context)
{
  m_impl->roiMode = frontend::isRoiMode(context.config().frontEnd.mode);
  TUpdate u;
  if (const auto gt = source.groundTruthFile(); gt && std::filesystem::exists(*gt))
  {
    try
    {
      u.groundTruth = io::loadTumTrajectory(*gt);
    }
    catch (const std::exception& e)
    {
      const std::string what = e.what();
      m_impl->log("warning: no ground truth in the view: " + what.substr(0, what.find('\n')));
    }
  }
  {
    std::lock_guard<std::mutex> lk(m_impl->mutex);
    m_impl->sequence = source.name() + ", " + frontend::toString(context.config().frontEnd.mode) +
                       ", " + features::toString(context.config().frontEnd.extractor.feature_type);
  }
  m_impl->win->setWindowTitle(m_impl->session.appName + ": " + source.name());
  m_impl->push(std::move(u));
  m_impl->statusDirty = true;
  m_impl->notify(m_impl->wake);
}

void CLiveView::onFrame(
    const frontend::TFrameResult& result, const io::TRGBDFrame& frame,
    const graphslam::CSlamContext& context)
{
  TImpl& I = *m_impl;
  const double now = secondsSince(I.start);
  const bool withImage = now - I.lastImageAt >= 0.999 * I.period;
  if (withImage)
    I.lastImageAt = now;
  TUpdate u;
  u.frame = makeLiveFrame(
      result, frame, context, withImage,
      static_cast<std::size_t>(I.options.map_points_per_keyframe), I.loopsSeen);
  u.frame->processedAt = now;
  I.loopsSeen = u.frame->loopClosures;
  I.push(std::move(u));
  I.waitWhilePaused();
}

void CLiveView::onOptimized(const graphslam::TGraph& graph, const graphslam::CSlamContext& context)
{
  TUpdate u;
  u.keyframePoses.emplace();
  for (const auto& [id, pose] : graph.nodes)
    (*u.keyframePoses)[id] = pose;
  u.loops = loopPairs(context);
  m_impl->loopsSeen = u.loops.size();
  m_impl->push(std::move(u));
}

bool CLiveView::stopRequested() const
{
  return m_impl->quit;
}

bool CLiveView::paused() const
{
  return m_impl->isPaused;
}

void CLiveView::saveScreenshot(const std::string& pngFile)
{
  auto done = std::make_shared<std::promise<void>>();
  auto result = done->get_future();
  {
    std::lock_guard<std::mutex> lk(m_impl->mutex);
    if (m_impl->stopDrawing)
      throw std::runtime_error("screenshot " + pngFile + ": the live view is closed");
    m_impl->shots.push_back({pngFile, done});
  }
  m_impl->wake.notify_all();
  result.get();
}

void CLiveView::setMessage(const std::string& text)
{
  {
    std::lock_guard<std::mutex> lk(m_impl->mutex);
    m_impl->message = text;
  }
  m_impl->statusDirty = true;
  m_impl->wake.notify_all();
}

void CLiveView::waitUntilClosed()
{
  std::unique_lock<std::mutex> lk(m_impl->mutex);
  m_impl->closed.wait(lk, [this] { return m_impl->quit.load(); });
}

void exitAfterLiveView(int code)
{
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  std::_Exit(code);
}
}  // namespace roislam::gui
