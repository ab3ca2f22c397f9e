/* Private: repaints only the children of MRPT's window frame (its OpenGL
 * canvas). MRPT's CDisplayWindow3D::forceRepaint() refreshes the whole
 * frame, and GTK 3 then paints the canvas twice: 82 buffer swaps for 40
 * requests, 19 ms of CPU each under Xvfb (Mesa's software GL), against
 * 42 swaps and 14 ms when only the canvas is refreshed. Needs wxWidgets'
 * headers (libwxgtk3.2-dev): built only when CMake finds them
 * (ROISLAM_GUI_WX_HEADERS); the live view falls back to forceRepaint().
 * Kept apart from MRPT's headers, whose config.h defines some of the same
 * macros as wx/setup.h. Called on MRPT's GUI thread only.
 */
#pragma once

namespace roislam::gui::detail
{
/** `frame`: CDisplayWindow3D::getWxObject() (a wxFrame*); null does nothing. */
void refreshChildren(void* frame);
}  // namespace roislam::gui::detail
