/* The X11 side of the live view, outside MRPT: whether a display can be
 * opened at all (so that --gui without one fails at once with one line,
 * instead of wxWidgets' GTK warning and MRPT's five-second timeout), and
 * a screenshot of this process's window read back from the X server
 * (MRPT 2.5 reads the window's front buffer with glReadPixels, which
 * gives black under Mesa's software GLX, as under Xvfb). Used by CLiveView.
 */
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace roislam::gui
{
/** A connection to the X display, to keep until the window has its own:
 *  an X server resets when its last client leaves, and refuses new ones
 *  meanwhile (2 of 6 parallel runs under Xvfb failed GTK's start after a
 *  check that had closed its connection). Throws std::runtime_error
 *  "--gui: cannot open X display '<name>' ..." (or "--gui: no display
 *  (DISPLAY is not set) ...") when no X display can be opened. */
std::shared_ptr<void> requireX11Display();

/** The pixels (BGR) of the largest viewable window of this process (its
 *  _NET_WM_PID), as the X server has them; nullopt when there is none (or
 *  no display). */
std::optional<cv::Mat> captureOwnWindow();
}  // namespace roislam::gui
