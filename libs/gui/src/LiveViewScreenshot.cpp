/* CLiveView::TImpl's screenshots (LiveViewImpl.h): the window read back
 * after two fresh paints (MRPT's capture, else the X server's pixels when
 * MRPT's comes out black) and written as a PNG. Called on the drawing
 * thread for saveScreenshot() and the 's' key.
 */
#include <roislam/common/TextFiles.h>
#include <roislam/gui/X11Display.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "LiveViewImpl.h"

namespace roislam::gui
{
namespace
{
/** A captured window is real when it is not one colour (MRPT's own capture
 *  gives black where the front buffer cannot be read back). */
bool hasContent(const cv::Mat& img)
{
  if (img.empty())
    return false;
  double lo[3], hi[3];
  std::vector<cv::Mat> ch;
  cv::split(img, ch);
  for (std::size_t c = 0; c < ch.size(); ++c)
  {
    cv::minMaxLoc(ch[c], &lo[c], &hi[c]);
    if (hi[c] > lo[c])
      return true;
  }
  return false;
}
}  // namespace

cv::Mat CLiveView::TImpl::capture()
{
  if (!win->isOpen())
    throw std::runtime_error("the window is closed");
  // Wait for two paints that started after the scene was updated: MRPT
  // stores a new image at each paint while capturing.
  win->captureImagesStart();
  auto previous = win->getLastWindowImagePtr();
  for (int paints = 0, tries = 0; paints < 2 && tries < 250; ++tries)
  {
    if (tries % 25 == 0)
      repaint();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const auto now = win->getLastWindowImagePtr();
    if (now && now != previous)
    {
      ++paints;
      previous = now;
      repaint();
    }
  }
  win->captureImagesStop();
  if (previous)
  {
    cv::Mat mrptImage = previous->asCvMat<cv::Mat>(mrpt::img::DEEP_COPY);
    if (hasContent(mrptImage))
      return mrptImage;
  }
  // MRPT's read-back came out black: the front buffer is not readable
  // (Mesa's software GLX, e.g. under Xvfb). The X server has the pixels.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  if (auto x = captureOwnWindow())
    return *x;
  throw std::runtime_error("cannot read the window back");
}

void CLiveView::TImpl::serve(const TShot& shot)
{
  try
  {
    const cv::Mat img = capture();
    std::vector<uchar> png;
    if (!cv::imencode(".png", img, png))
      throw std::runtime_error("PNG encoding failed");
    const auto dir = std::filesystem::path(shot.file).parent_path();
    if (!dir.empty())
      std::filesystem::create_directories(dir);
    common::writeFileAtomically(shot.file, std::string(png.begin(), png.end()));
    if (shot.done)
      shot.done->set_value();
    else
      log("screenshot " + shot.file);
  }
  catch (const std::exception& e)
  {
    const std::string what = e.what();
    if (shot.done)
      shot.done->set_exception(std::make_exception_ptr(
          std::runtime_error("screenshot " + shot.file + ": " + what.substr(0, what.find('\n')))));
    else
      log("warning: screenshot " + shot.file + ": " + what.substr(0, what.find('\n')));
  }
}
}  // namespace roislam::gui
