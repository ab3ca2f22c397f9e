#include "roislam/gui/X11Display.h"

#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <unistd.h>

#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <vector>

namespace roislam::gui
{
namespace
{
struct TDisplayCloser
{
  void operator()(Display* d) const { XCloseDisplay(d); }
};
using TDisplayPtr = std::unique_ptr<Display, TDisplayCloser>;

std::optional<long> windowPid(Display* d, Window w)
{
  const Atom pidAtom = XInternAtom(d, "_NET_WM_PID", True);
  if (pidAtom == None)
    return std::nullopt;
  Atom type;
  int format;
  unsigned long n = 0, after = 0;
  unsigned char* data = nullptr;
  std::optional<long> pid;
  if (XGetWindowProperty(
          d, w, pidAtom, 0, 1, False, XA_CARDINAL, &type, &format, &n, &after, &data) == Success &&
      data && n == 1 && format == 32)
    pid = *reinterpret_cast<long*>(data);
  if (data)
    XFree(data);
  return pid;
}

/** The largest viewable window of this process, searched depth-first (a
 *  window manager reparents top-levels into its frames). */
void findWindow(Display* d, Window w, Window& best, long& bestArea)
{
  XWindowAttributes a;
  if (XGetWindowAttributes(d, w, &a) && a.map_state == IsViewable &&
      windowPid(d, w) == static_cast<long>(getpid()) &&
      static_cast<long>(a.width) * a.height > bestArea)
  {
    best = w;
    bestArea = static_cast<long>(a.width) * a.height;
  }
  Window root, parent, *children = nullptr;
  unsigned int n = 0;
  if (!XQueryTree(d, w, &root, &parent, &children, &n))
    return;
  for (unsigned int i = 0; i < n; ++i)
    findWindow(d, children[i], best, bestArea);
  if (children)
    XFree(children);
}

/** One channel of an X pixel as 8 bits, from its mask. */
uint8_t channel(unsigned long pixel, unsigned long mask)
{
  if (!mask)
    return 0;
  int shift = 0;
  while (!((mask >> shift) & 1))
    ++shift;
  const unsigned long max = mask >> shift;
  return static_cast<uint8_t>(((pixel & mask) >> shift) * 255 / max);
}
}  // namespace

std::shared_ptr<void> requireX11Display()
{
  const char* name = std::getenv("DISPLAY");
  if (!name || !*name)
    throw std::runtime_error(
        "--gui: no display (DISPLAY is not set); run without --gui, or under xvfb-run");
  Display* d = XOpenDisplay(nullptr);
  if (!d)
    throw std::runtime_error(
        std::string("--gui: cannot open X display '") + name +
        "'; run without --gui, or under xvfb-run");
  return std::shared_ptr<void>(d, [](void* p) { XCloseDisplay(static_cast<Display*>(p)); });
}

std::optional<cv::Mat> captureOwnWindow()
{
  TDisplayPtr d(XOpenDisplay(nullptr));
  if (!d)
    return std::nullopt;
  Window best = 0;
  long area = 0;
  findWindow(d.get(), DefaultRootWindow(d.get()), best, area);
  if (!best)
    return std::nullopt;
  XWindowAttributes a;
  if (!XGetWindowAttributes(d.get(), best, &a) || a.width <= 0 || a.height <= 0)
    return std::nullopt;
  XImage* img = XGetImage(
      d.get(), best, 0, 0, static_cast<unsigned>(a.width), static_cast<unsigned>(a.height),
      AllPlanes, ZPixmap);
  if (!img)
    return std::nullopt;
  cv::Mat out(a.height, a.width, CV_8UC3);
  for (int y = 0; y < a.height; ++y)
  {
    auto* row = out.ptr<cv::Vec3b>(y);
    for (int x = 0; x < a.width; ++x)
    {
      const unsigned long p = XGetPixel(img, x, y);
      row[x] = {channel(p, img->blue_mask), channel(p, img->green_mask), channel(p, img->red_mask)};
    }
  }
  XDestroyImage(img);
  return out;
}
}  // namespace roislam::gui
