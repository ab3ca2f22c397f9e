/* roi-graphslam --gui (and roi-graphslam-engine --gui) end to end, as a user runs it, on a private
 * Xvfb (share/scripts/with-xvfb.sh is this test's launcher): the synthetic loop runs to the end
 * with the window open and writes the same trajectory as without it, byte for byte, and the
 * window's screenshot shows the map and the images; the keys (space, s, q, sent by xdotool as a
 * user's keyboard would) pause, save a screenshot and stop the run with every output written;
 * closing the window (the WM_DELETE_WINDOW a window manager sends) stops it the same way; without a
 * display --gui fails with one line and writes nothing. Display tests skip when DISPLAY is not set
 * (no Xvfb). */
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

// Last: Xlib's macros (None, Status...) clash with GoogleTest's names.
#include <X11/Xatom.h>
#include <X11/Xlib.h>

extern char** environ;

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace
{
std::string exe(const std::string& app = "roi-graphslam")
{
  return roislam::testing::binaryDir() + "/apps/" + app + "/" + app;
}

std::string config(const std::string& name)
{
  return roislam::testing::sourceDir() + "/config/" + name;
}

std::string readText(const std::string& file)
{
  std::ifstream f(file, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

/** roi-graphslam running in the background (through `sh -c exec`, so that
 *  the pid is the app's own: its window carries it as _NET_WM_PID). */
class CAppProcess
{
 public:
  /** `command`: the executable and its arguments. */
  CAppProcess(
      const std::string& command, const std::string& errFile, const std::string& envPrefix = "")
  {
    const std::string cmd = envPrefix + "exec " + command + " > /dev/null 2> " + errFile;
    const char* argv[] = {"/bin/sh", "-c", cmd.c_str(), nullptr};
    if (posix_spawn(&m_pid, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ) != 0)
      m_pid = -1;
  }
  ~CAppProcess()
  {
    if (m_pid > 0 && !m_exit)
    {
      kill(m_pid, SIGKILL);
      waitpid(m_pid, nullptr, 0);
    }
  }
  pid_t pid() const { return m_pid; }
  /** The exit code, or nullopt when it did not end within `timeout`
   *  (-1: killed by a signal). */
  std::optional<int> wait(std::chrono::seconds timeout)
  {
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (!m_exit && std::chrono::steady_clock::now() < until)
    {
      int status = 0;
      if (waitpid(m_pid, &status, WNOHANG) == m_pid)
        m_exit = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      else
        std::this_thread::sleep_for(20ms);
    }
    return m_exit;
  }

 private:
  pid_t m_pid = -1;
  std::optional<int> m_exit;
};

/** roi-graphslam with `args`, to its end. */
int runApp(const std::string& args, const std::string& errFile, const std::string& envPrefix = "")
{
  CAppProcess p(exe() + " " + args, errFile, envPrefix);
  return p.wait(300s).value_or(-2);
}

/** The process's top-level window on the test's display (0 until mapped). */
class CXClient
{
 public:
  CXClient() : m_d(XOpenDisplay(nullptr)) {}
  ~CXClient()
  {
    if (m_d)
      XCloseDisplay(m_d);
  }
  bool ok() const { return m_d != nullptr; }

  /** Polls until a viewable window with _NET_WM_PID == pid exists. */
  Window waitForWindow(pid_t pid, std::chrono::seconds timeout)
  {
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < until)
    {
      Window w = 0;
      find(DefaultRootWindow(m_d), pid, w);
      if (w)
        return w;
      std::this_thread::sleep_for(50ms);
    }
    return 0;
  }

  /** What a window manager sends when the user clicks the close button. */
  void requestClose(Window w)
  {
    XEvent e{};
    e.xclient.type = ClientMessage;
    e.xclient.window = w;
    e.xclient.message_type = XInternAtom(m_d, "WM_PROTOCOLS", False);
    e.xclient.format = 32;
    e.xclient.data.l[0] = static_cast<long>(XInternAtom(m_d, "WM_DELETE_WINDOW", False));
    e.xclient.data.l[1] = CurrentTime;
    XSendEvent(m_d, w, False, NoEventMask, &e);
    XFlush(m_d);
  }

 private:
  void find(Window w, pid_t pid, Window& found)
  {
    if (found)
      return;
    XWindowAttributes a;
    if (XGetWindowAttributes(m_d, w, &a) && a.map_state == IsViewable && pidOf(w) == pid &&
        a.width > 300)
    {
      found = w;
      return;
    }
    Window root, parent, *children = nullptr;
    unsigned int n = 0;
    if (!XQueryTree(m_d, w, &root, &parent, &children, &n))
      return;
    for (unsigned int i = 0; i < n; ++i)
      find(children[i], pid, found);
    if (children)
      XFree(children);
  }
  long pidOf(Window w)
  {
    const Atom pidAtom = XInternAtom(m_d, "_NET_WM_PID", True);
    if (pidAtom == None)
      return -1;
    Atom type;
    int format;
    unsigned long n = 0, after = 0;
    unsigned char* data = nullptr;
    long pid = -1;
    if (XGetWindowProperty(
            m_d, w, pidAtom, 0, 1, False, XA_CARDINAL, &type, &format, &n, &after, &data) ==
            Success &&
        data && n == 1 && format == 32)
      pid = *reinterpret_cast<long*>(data);
    if (data)
      XFree(data);
    return pid;
  }
  Display* m_d;
};

#ifdef ROISLAM_XDOTOOL
/** Keys as a user types them: focus on the window, then XTest key events. */
bool sendKeys(Window w, const std::string& keys)
{
  const std::string cmd = std::string(ROISLAM_XDOTOOL) + " windowfocus --sync " +
                          std::to_string(w) + " key --delay 50 " + keys + " > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  EXPECT_EQ(rc, 0) << cmd;
  return rc == 0;
}

/** Presses `key` until `seen()` holds, as a user presses a key again that
 *  did nothing: a synthetic key can go unseen (in CI, on a loaded 2-core
 *  machine, Xvfb once lost a space that came right after windowfocus while
 *  the key after it arrived). The app answers a key within milliseconds, so
 *  `patience` without its effect means the key was lost, and pressing a
 *  toggle (space) again cannot undo one that was seen. A key whose effect
 *  takes work (s: rendering and saving a screenshot) gets more patience. */
bool pressUntil(
    Window w, const std::string& key, const std::function<bool()>& seen,
    std::chrono::seconds patience = 3s)
{
  for (int attempt = 0; attempt < 4; ++attempt)
  {
    if (!sendKeys(w, key))
      return false;
    const auto until = std::chrono::steady_clock::now() + patience;
    for (; std::chrono::steady_clock::now() < until; std::this_thread::sleep_for(20ms))
      if (seen())
        return true;
  }
  return seen();
}
#endif

/** Pixels of `roi` that differ from `bgr` by more than 40 in a channel. */
double shareUnlike(const cv::Mat& img, const cv::Rect& roi, const cv::Vec3b& bgr)
{
  std::size_t n = 0;
  for (int y = roi.y; y < roi.y + roi.height; ++y)
    for (int x = roi.x; x < roi.x + roi.width; ++x)
    {
      const auto p = img.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - bgr[0]) > 40 || std::abs(p[1] - bgr[1]) > 40 ||
          std::abs(p[2] - bgr[2]) > 40)
        ++n;
    }
  return static_cast<double>(n) / roi.area();
}

std::size_t dataLines(const std::string& file)
{
  std::istringstream in(readText(file));
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);)
    n += !line.empty() && line[0] != '#';
  return n;
}

/** Every output of a run is there and agrees with summary.json (the run's
 *  frames, tracked frames and poses). Returns the summary. */
nlohmann::json expectCompleteOutputs(const std::string& out)
{
  for (const char* f :
       {"trajectory.txt", "graph.graph", "map.bt", "scene.3Dscene", "snapshot.png", "frames.csv",
        "summary.json"})
  {
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
    EXPECT_FALSE(fs::exists(out + "/" + f + ".tmp")) << f;
  }
  const auto s = nlohmann::json::parse(readText(out + "/summary.json"));
  EXPECT_EQ(dataLines(out + "/trajectory.txt"), s["tracked_frames"].get<std::size_t>());
  EXPECT_EQ(dataLines(out + "/frames.csv"), s["frames"].get<std::size_t>() + 1);  // + header
  EXPECT_FALSE(cv::imread(out + "/snapshot.png").empty());
  return s;
}

/** roi-graphslam on `seq` into `out` with the window open, paused after
 *  its first frame (space starts it). */
std::string pausedRunCommand(const std::string& seq, const std::string& out)
{
  // --allow-partial: a run stopped after a few frames is too short to
  // evaluate (exit 3 otherwise); the outputs are what these tests check.
  return exe() + " --ini " + config("roi_small.ini") + " --input " + seq + " --output-dir " + out +
         " --gui-paused --allow-partial";
}

#define ROISLAM_REQUIRE_DISPLAY()                                                       \
  if (!std::getenv("DISPLAY"))                                                          \
  GTEST_SKIP() << "no X display (install xvfb: the test runs under share/scripts/with-" \
                  "xvfb.sh then)"
}  // namespace

TEST(LiveView, GuiRunEqualsHeadlessAndScreenshotShowsMapAndImages)
{
  ROISLAM_REQUIRE_DISPLAY();
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string dir = roislam::testing::makeTempDir("gui_equal");
  const std::string common = "--ini " + config("roi_small.ini") + " --input " + seq;
  ASSERT_EQ(runApp(common + " --output-dir " + dir + "/headless", dir + "/h.err"), 0)
      << readText(dir + "/h.err");
  const std::string shot = dir + "/window.png";
  ASSERT_EQ(
      runApp(
          common + " --output-dir " + dir + "/gui --gui --gui-screenshot " + shot, dir + "/g.err"),
      0)
      << readText(dir + "/g.err");

  const auto s = expectCompleteOutputs(dir + "/gui");
  EXPECT_EQ(s["frames"].get<int>(), 90);
  EXPECT_FALSE(s["stopped_by_user"].get<bool>());
  const std::string traj = readText(dir + "/headless/trajectory.txt");
  ASSERT_FALSE(traj.empty());
  EXPECT_EQ(readText(dir + "/gui/trajectory.txt"), traj) << "--gui changed the trajectory";
  EXPECT_EQ(readText(dir + "/gui/graph.graph"), readText(dir + "/headless/graph.graph"));

  // The window: the 3-D map on the left (background 0.1, 0.1, 0.12), the
  // colour image top right and the depth image below it (on black).
  const cv::Mat img = cv::imread(shot);
  ASSERT_FALSE(img.empty()) << shot;
  EXPECT_EQ(img.cols, 1024);
  EXPECT_EQ(img.rows, 576);
  const int column = img.cols * 3 / 8;  // CLiveView's image column
  const int mapW = img.cols - column;
  // Inside the map area, away from the text lines at its top and bottom.
  const cv::Rect map(mapW / 8, img.rows / 8, mapW * 3 / 4, img.rows * 3 / 4);
  const double mapShare = shareUnlike(img, map, {31, 26, 26});
  EXPECT_GT(mapShare, 0.05) << "map area mostly background";
  const cv::Rect colour(mapW + 8, 8, column - 16, img.rows / 2 - 16);
  EXPECT_GT(shareUnlike(img, colour, {0, 0, 0}), 0.5) << "colour image missing";
  const cv::Rect depth(mapW + 8, img.rows / 2 + 8, column - 16, img.rows / 2 - 16);
  EXPECT_GT(shareUnlike(img, depth, {0, 0, 0}), 0.3) << "depth image missing";
  // The view said how much it cost.
  EXPECT_NE(readText(dir + "/g.err").find("live view: "), std::string::npos);
  fs::remove_all(dir);
}

TEST(LiveView, EngineAppGuiRunEqualsHeadless)
{
  ROISLAM_REQUIRE_DISPLAY();
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string dir = roislam::testing::makeTempDir("gui_engine");
  const std::string common =
      exe("roi-graphslam-engine") + " -i " + config("graphslam-engine.ini") + " -r " + seq;
  CAppProcess headless(common + " --output-dir " + dir + "/headless", dir + "/h.err");
  ASSERT_EQ(headless.wait(300s), std::optional<int>(0)) << readText(dir + "/h.err");
  const std::string shot = dir + "/window.png";
  CAppProcess gui(
      common + " --output-dir " + dir + "/gui --gui-screenshot " + shot, dir + "/g.err");
  ASSERT_EQ(gui.wait(300s), std::optional<int>(0)) << readText(dir + "/g.err");

  const auto s = expectCompleteOutputs(dir + "/gui");
  EXPECT_EQ(s["frames"].get<int>(), 90);
  const std::string traj = readText(dir + "/headless/trajectory.txt");
  ASSERT_FALSE(traj.empty());
  EXPECT_EQ(readText(dir + "/gui/trajectory.txt"), traj) << "--gui changed the trajectory";
  const cv::Mat img = cv::imread(shot);
  ASSERT_FALSE(img.empty()) << shot;
  EXPECT_EQ(img.cols, 1024);
  EXPECT_NE(readText(dir + "/g.err").find("live view: "), std::string::npos);
  fs::remove_all(dir);
}

TEST(LiveView, NoDisplayGivesOneLineAndWritesNothing)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string dir = roislam::testing::makeTempDir("gui_nodisplay");
  const std::string out = dir + "/out";
  const std::string args = "--input " + seq + " --output-dir " + out + " --gui";
  for (const std::string env : {"unset DISPLAY; ", "export DISPLAY=:4093; "})
  {
    EXPECT_EQ(runApp(args, dir + "/err", env), 1) << env;
    const std::string err = readText(dir + "/err");
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_EQ(err.rfind("roi-graphslam: error: --gui: ", 0), 0u) << err;
    EXPECT_FALSE(fs::exists(out)) << env << "made " << out;
  }
  fs::remove_all(dir);
}

#ifdef ROISLAM_XDOTOOL
TEST(LiveView, KeysPauseScreenshotAndQuitWithCompleteOutputs)
{
  ROISLAM_REQUIRE_DISPLAY();
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string dir = roislam::testing::makeTempDir("gui_keys");
  const std::string out = dir + "/out";
  CXClient x;
  ASSERT_TRUE(x.ok());
  // Paused from the start: the run waits after its first frame.
  CAppProcess app(pausedRunCommand(seq, out), dir + "/err");
  const Window w = x.waitForWindow(app.pid(), 60s);
  ASSERT_NE(w, 0u) << readText(dir + "/err");
  // space: run a while; space: pause again (mid-run on any machine: the
  // 90 frames take seconds); s: a screenshot; q once it is saved. Each key
  // is seen by its line in the app's log (or its file) before the next.
  const std::string errFile = dir + "/err";
  const auto logs = [&errFile](const std::string& line)
  { return [&errFile, line] { return readText(errFile).find(line) != std::string::npos; }; };
  ASSERT_TRUE(pressUntil(w, "space", logs(": resumed"))) << readText(errFile);
  std::this_thread::sleep_for(500ms);
  ASSERT_TRUE(pressUntil(w, "space", logs(": paused (space resumes)"))) << readText(errFile);
  // While the run goes on the output folder is staged beside `out`
  // (COutputFolder): the screenshot is in there until the rename.
  const auto hasScreenshot = [](const std::string& folder, bool recursive)
  {
    std::error_code ec;
    const auto isShot = [](const fs::path& p)
    { return p.filename().string().rfind("screenshot-", 0) == 0; };
    if (recursive)
    {
      for (const auto& e : fs::recursive_directory_iterator(folder, ec))
        if (isShot(e.path()))
          return true;
    }
    else
      for (const auto& e : fs::directory_iterator(folder, ec))
        if (isShot(e.path()))
          return true;
    return false;
  };
  EXPECT_TRUE(pressUntil(
      w, "s", [&dir, &hasScreenshot] { return hasScreenshot(dir, true); }, 10s))
      << "s saved no screenshot-*.png under " << dir;
  EXPECT_TRUE(pressUntil(w, "q", logs(": q: stopping the run"))) << readText(errFile);
  ASSERT_EQ(app.wait(120s), std::optional<int>(0)) << readText(dir + "/err");
  EXPECT_TRUE(hasScreenshot(out, false)) << "the screenshot did not move into " << out;

  const auto s = expectCompleteOutputs(out);
  EXPECT_TRUE(s["stopped_by_user"].get<bool>());
  EXPECT_GT(s["frames"].get<int>(), 1);
  EXPECT_LT(s["frames"].get<int>(), 90);
  const std::string err = readText(dir + "/err");
  EXPECT_NE(err.find("paused"), std::string::npos) << err;
  EXPECT_NE(err.find("q: stopping the run"), std::string::npos) << err;
  fs::remove_all(dir);
}
#endif

TEST(LiveView, ClosingTheWindowEndsTheRunCleanly)
{
  ROISLAM_REQUIRE_DISPLAY();
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string dir = roislam::testing::makeTempDir("gui_close");
  const std::string out = dir + "/out";
  CXClient x;
  ASSERT_TRUE(x.ok());
  CAppProcess app(pausedRunCommand(seq, out), dir + "/err");
  const Window w = x.waitForWindow(app.pid(), 60s);
  ASSERT_NE(w, 0u) << readText(dir + "/err");
  // Paused after the first frame: the close request arrives mid-run.
  std::this_thread::sleep_for(300ms);
  x.requestClose(w);
  ASSERT_EQ(app.wait(120s), std::optional<int>(0)) << readText(dir + "/err");
  const auto s = expectCompleteOutputs(out);
  EXPECT_TRUE(s["stopped_by_user"].get<bool>());
  EXPECT_LT(s["frames"].get<int>(), 90);
  const std::string err = readText(dir + "/err");
  EXPECT_NE(err.find("window closed: stopping the run"), std::string::npos) << err;
  fs::remove_all(dir);
}
