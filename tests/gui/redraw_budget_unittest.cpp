/* The live view's CPU budget (CRedrawBudget): the redraw period grows when
 * the view's threads use more than their share of the rest's CPU and comes
 * back to 1 / refresh_hz when they use less; and the per-thread CPU read
 * from /proc finds a busy thread by its name. Also [LiveView]'s ini
 * checks. */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <pthread.h>
#include <roislam/gui/CLiveView.h>
#include <roislam/gui/CRedrawBudget.h>
#include <roislam/testing/TestData.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>
#include <tuple>

using roislam::gui::CRedrawBudget;

TEST(RedrawBudget, SlowsDownOverShareAndRecovers)
{
  CRedrawBudget b(0.5, 2.0, 0.1);
  double view = 0, process = 0;
  EXPECT_DOUBLE_EQ(b.update(view, process), 0.5);
  // The view used 0.3 s while the rest used 1 s: 3x its share -> slower.
  view += 0.3;
  process += 1.3;
  EXPECT_NEAR(b.update(view, process), 1.0, 1e-9);  // x2 at most per step
  view += 0.3;
  process += 1.3;
  EXPECT_NEAR(b.update(view, process), 2.0, 1e-9);  // capped at the maximum
  // Too little of the rest's CPU to judge (paused): unchanged.
  view += 0.1;
  process += 0.2;
  EXPECT_NEAR(b.update(view, process), 2.0, 1e-9);
  // Well under the share: back towards 1 / refresh_hz.
  for (int i = 0; i < 20; ++i)
  {
    view += 0.01;
    process += 1.01;
    b.update(view, process);
  }
  EXPECT_NEAR(b.period(), 0.5, 1e-9);
}

TEST(RedrawBudget, ThreadCpuFindsABusyThreadByName)
{
  std::atomic<bool> stop{false};
  std::thread busy(
      [&]
      {
        pthread_setname_np(pthread_self(), "budget-test");
        volatile double x = 0;
        while (!stop)
          x = x + std::sqrt(x + 1.0);
      });
  // Until the busy thread has had 0.1 s of CPU by its own clock (a loaded
  // machine gives it less than the wall time), at most 20 s.
  double mine = 0, process = 0;
  for (int i = 0; i < 400 && mine < 0.1; ++i)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::tie(mine, process) = roislam::gui::threadCpuSeconds({"budget-test"});
  }
  const auto [none, process2] = roislam::gui::threadCpuSeconds({"no-such-thread"});
  stop = true;
  busy.join();
  EXPECT_GE(mine, 0.1);
  EXPECT_LE(mine, process + 0.02);
  EXPECT_EQ(none, 0.0);
  EXPECT_GE(process2, process);
}

TEST(LiveViewOptions, IniKeysAreCheckedAndValidated)
{
  const std::string dir = roislam::testing::makeTempDir("liveview_ini");
  const auto write = [&](const std::string& text)
  {
    std::ofstream(dir + "/v.ini") << text;
    return dir + "/v.ini";
  };
  const auto o =
      roislam::gui::CLiveView::loadOptions(write("[LiveView]\nrefresh_hz = 5\nfollow = false\n"));
  EXPECT_DOUBLE_EQ(o.refresh_hz, 5);
  EXPECT_FALSE(o.follow);
  EXPECT_DOUBLE_EQ(roislam::gui::CLiveView::loadOptions("").max_cpu_share, 0.03);
  try
  {
    roislam::gui::CLiveView::loadOptions(write("[LiveView]\nrefresh_hzz = 5\n"));
    FAIL() << "unknown key accepted";
  }
  catch (const std::exception& e)
  {
    EXPECT_NE(std::string(e.what()).find("[LiveView] unknown key 'refresh_hzz'"), std::string::npos)
        << e.what();
  }
  try
  {
    roislam::gui::CLiveView::loadOptions(write("[LiveView]\nrefresh_hz = 0\n"));
    FAIL() << "refresh_hz = 0 accepted";
  }
  catch (const std::exception& e)
  {
    EXPECT_NE(std::string(e.what()).find("[LiveView] refresh_hz"), std::string::npos) << e.what();
  }
  try
  {
    roislam::gui::CLiveView::loadOptions(write("[LiveView]\nwidth = wide\n"));
    FAIL() << "width = wide accepted";
  }
  catch (const std::exception& e)
  {
    EXPECT_NE(std::string(e.what()).find("[LiveView] width"), std::string::npos) << e.what();
  }
}
