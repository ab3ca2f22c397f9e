#include "roislam/gui/CLiveViewSession.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <stdexcept>
#if ROISLAM_HAVE_GUI
#include "roislam/gui/CLiveView.h"
#endif

namespace roislam::gui
{
CLiveViewSession::CLiveViewSession(std::string appName) : m_appName(std::move(appName)) {}

CLiveViewSession::~CLiveViewSession() = default;

void CLiveViewSession::addFlags(CLI::App& cli)
{
  cli.add_flag("--gui", m_request.gui, "Live view while SLAM runs (needs an X display)");
  cli.add_flag("--gui-paused", m_request.paused, "--gui, starting paused (space starts the run)");
  cli.add_option(
      "--gui-screenshot", m_request.screenshot, "--gui: save the window as PNG at the end");
  cli.add_flag("--gui-keep-open", m_request.keepOpen, "--gui: keep the window open after the run");
}

void CLiveViewSession::open(const std::string& iniFile, const std::string& outputDir)
{
  if (!m_request.wanted() || m_view)
    return;
#if ROISLAM_HAVE_GUI
  CLiveView::TSession session;
  session.appName = m_appName;
  session.screenshotDir = outputDir;
  session.startPaused = m_request.paused;
  session.log = [](const std::string& line) { std::cerr << line << std::endl; };
  auto view = std::make_unique<CLiveView>(CLiveView::loadOptions(iniFile), session);
  m_window = view.get();
  m_view = std::move(view);
#else
  (void)iniFile;
  (void)outputDir;
  throw std::runtime_error(
      "--gui: " + m_appName + " was built without GUI (MRPT's wxWidgets windows were not found)");
#endif
}

graphslam::CSlamObserver* CLiveViewSession::observer() const
{
  return m_view.get();
}

void CLiveViewSession::finish(const std::string& outputDir)
{
#if ROISLAM_HAVE_GUI
  if (!m_window)
    return;
  m_window->setMessage(
      "finished: outputs in " + outputDir +
      (m_request.keepOpen ? "   (q or closing the window ends)" : ""));
  if (!m_request.screenshot.empty())
  {
    try
    {
      m_window->saveScreenshot(m_request.screenshot);
    }
    catch (const std::exception& e)
    {
      std::cerr << m_appName << ": warning: " << e.what() << std::endl;
    }
  }
  if (m_request.keepOpen)
    m_window->waitUntilClosed();
#else
  (void)outputDir;
#endif
}

int CLiveViewSession::end(int rc)
{
  if (!m_view)
    return rc;
  m_window = nullptr;
  m_view.reset();
#if ROISLAM_HAVE_GUI
  exitAfterLiveView(rc);
#else
  return rc;
#endif
}
}  // namespace roislam::gui
