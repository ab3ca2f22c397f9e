#include "roislam/sim/ProceduralTextures.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

namespace roislam::sim
{
namespace
{
int randInt(mrpt::random::CRandomGenerator& rng, int lo, int hi)  // inclusive
{
  return lo + static_cast<int>(rng.drawUniform32bit() % static_cast<uint32_t>(hi - lo + 1));
}

cv::Scalar randColour(mrpt::random::CRandomGenerator& rng, int lo, int hi)
{
  return cv::Scalar(randInt(rng, lo, hi), randInt(rng, lo, hi), randInt(rng, lo, hi));
}

/** A saturated colour: one channel high, one low, one random. */
cv::Scalar vividColour(mrpt::random::CRandomGenerator& rng)
{
  int c[3] = {randInt(rng, 0, 255), randInt(rng, 0, 60), randInt(rng, 190, 255)};
  for (int i = 2; i > 0; --i)
    std::swap(c[i], c[randInt(rng, 0, i)]);
  return cv::Scalar(c[0], c[1], c[2]);
}

std::string randomWord(mrpt::random::CRandomGenerator& rng, int minLen, int maxLen)
{
  static const char* kLetters = "etaoinshrdlucmfwypvbgkjqxz";
  const int n = randInt(rng, minLen, maxLen);
  std::string w;
  for (int i = 0; i < n; ++i)
  {
    // Skewed towards frequent letters, like real text.
    const double r = rng.drawUniform(0.0, 1.0);
    w += kLetters[static_cast<int>(r * r * 26) % 26];
  }
  if (randInt(rng, 0, 5) == 0)
    w[0] = static_cast<char>(std::toupper(w[0]));
  return w;
}

const int kFonts[] = {
    cv::FONT_HERSHEY_SIMPLEX, cv::FONT_HERSHEY_DUPLEX, cv::FONT_HERSHEY_COMPLEX,
    cv::FONT_HERSHEY_TRIPLEX};

/** Font scale whose capital letters are about heightPx tall. */
double fontScaleFor(int font, double heightPx)
{
  int baseline = 0;
  const cv::Size s = cv::getTextSize("H", font, 1.0, 1, &baseline);
  return heightPx / std::max(1, s.height);
}

/** Writes random words along one line from x0 to at most x1. */
void writeLine(
    mrpt::random::CRandomGenerator& rng, cv::Mat& img, int x0, int x1, int baselineY, int font,
    double capHeightPx, const cv::Scalar& ink)
{
  const double scale = fontScaleFor(font, capHeightPx);
  const int thickness = std::max(1, static_cast<int>(std::lround(capHeightPx / 9.0)));
  int baseline = 0;
  const int space = std::max(2, static_cast<int>(capHeightPx * 0.6));
  int x = x0;
  // Ragged right margin: lines end at a random point of the last 30 %.
  const int xEnd = x1 - static_cast<int>(rng.drawUniform(0.0, 0.3) * (x1 - x0));
  while (true)
  {
    const std::string w = randomWord(rng, 1, 9);
    const cv::Size s = cv::getTextSize(w, font, scale, thickness, &baseline);
    if (x + s.width > xEnd)
      break;
    cv::putText(img, w, cv::Point(x, baselineY), font, scale, ink, thickness, cv::LINE_AA);
    x += s.width + space;
  }
}
}  // namespace

cv::Mat makeNoiseTexture(
    mrpt::random::CRandomGenerator& rng, cv::Size size, const cv::Scalar& base, double contrast,
    int finestCellPx)
{
  cv::Mat acc = cv::Mat::zeros(size, CV_32F);
  int octaves = 0;
  for (int cell = std::max(1, finestCellPx); cell <= std::max(size.width, size.height) / 4;
       cell *= 2, ++octaves)
  {
    cv::Mat grid(size.height / cell + 3, size.width / cell + 3, CV_32F);
    for (int r = 0; r < grid.rows; ++r)
      for (int c = 0; c < grid.cols; ++c)
        grid.at<float>(r, c) = static_cast<float>(rng.drawUniform(-1.0, 1.0));
    cv::Mat up;
    cv::resize(
        grid, up, cv::Size(grid.cols * cell, grid.rows * cell), 0, 0,
        cell == 1 ? cv::INTER_NEAREST : cv::INTER_CUBIC);
    acc += up(cv::Rect(cell, cell, size.width, size.height));
  }
  if (octaves > 0)
    acc *= 1.0 / std::sqrt(static_cast<double>(octaves));
  cv::Mat out(size, CV_8UC3);
  for (int r = 0; r < size.height; ++r)
  {
    const float* a = acc.ptr<float>(r);
    auto* o = out.ptr<cv::Vec3b>(r);
    for (int c = 0; c < size.width; ++c)
      for (int k = 0; k < 3; ++k)
        o[c][k] = cv::saturate_cast<uchar>(base[k] + contrast * a[c]);
  }
  return out;
}

cv::Mat makeTextPage(mrpt::random::CRandomGenerator& rng, cv::Size size, double lineHeightPx)
{
  const cv::Scalar paper(randInt(rng, 225, 250), randInt(rng, 235, 252), randInt(rng, 238, 255));
  cv::Mat img(size, CV_8UC3, paper);
  const cv::Scalar ink = randInt(rng, 0, 2) == 0 ? cv::Scalar(90, 30, 20) : randColour(rng, 0, 40);
  const int font = kFonts[randInt(rng, 0, 3)];
  const int margin = static_cast<int>(std::max(4.0, 1.5 * lineHeightPx));
  const int x0 = margin, x1 = size.width - margin;
  double y = margin;
  bool first = true;
  while (y + 2 * lineHeightPx < size.height - margin)
  {
    const int kind = first ? 0 : randInt(rng, 0, 9);
    first = false;
    if (kind == 0)
    {  // heading
      const double h = lineHeightPx * rng.drawUniform(1.3, 2.0);
      y += h * 1.4;
      writeLine(
          rng, img, x0, x0 + static_cast<int>((x1 - x0) * 0.7), static_cast<int>(y), font, h, ink);
      y += h * 0.8;
    }
    else if (kind == 1 && y + 6 * lineHeightPx < size.height - margin)
    {  // figure: a framed box with shapes
      const int fh = static_cast<int>(lineHeightPx * randInt(rng, 3, 6));
      const int fw = static_cast<int>((x1 - x0) * rng.drawUniform(0.3, 0.6));
      const int fx = randInt(rng, 0, 1) ? x0 : x1 - fw;
      const cv::Rect r(fx, static_cast<int>(y + lineHeightPx * 0.5), fw, fh);
      cv::rectangle(img, r, vividColour(rng), cv::FILLED);
      for (int i = 0; i < 4; ++i)
        cv::circle(
            img, cv::Point(r.x + randInt(rng, 0, fw), r.y + randInt(rng, 0, fh)),
            randInt(rng, 2, std::max(3, fh / 3)), vividColour(rng), cv::FILLED, cv::LINE_AA);
      cv::rectangle(img, r, ink, std::max(1, static_cast<int>(lineHeightPx / 8)));
      y += fh + lineHeightPx;
    }
    else
    {  // paragraph
      const int lines = randInt(rng, 2, 6);
      for (int l = 0; l < lines && y + 2 * lineHeightPx < size.height - margin; ++l)
      {
        y += lineHeightPx * 1.45;
        writeLine(rng, img, x0, x1, static_cast<int>(y), font, lineHeightPx * 0.72, ink);
      }
      y += lineHeightPx * 0.8;
    }
  }
  return img;
}

cv::Mat makePoster(mrpt::random::CRandomGenerator& rng, cv::Size size)
{
  const cv::Scalar c0 = randColour(rng, 20, 235), c1 = randColour(rng, 20, 235);
  cv::Mat img(size, CV_8UC3);
  for (int r = 0; r < size.height; ++r)
  {
    const double t = static_cast<double>(r) / std::max(1, size.height - 1);
    img.row(r).setTo(c0 * (1 - t) + c1 * t);
  }
  const int minDim = std::min(size.width, size.height);
  const int shapes = randInt(rng, 6, 12);
  for (int i = 0; i < shapes; ++i)
  {
    const cv::Point p(randInt(rng, 0, size.width), randInt(rng, size.height / 5, size.height));
    const int s = randInt(rng, minDim / 20, minDim / 4);
    switch (randInt(rng, 0, 2))
    {
      case 0:
        cv::circle(img, p, s, vividColour(rng), cv::FILLED, cv::LINE_AA);
        break;
      case 1:
        cv::rectangle(img, cv::Rect(p.x - s, p.y - s / 2, 2 * s, s), vividColour(rng), cv::FILLED);
        break;
      default:
      {
        std::vector<cv::Point> poly;
        for (int k = 0; k < 3; ++k)
          poly.emplace_back(p.x + randInt(rng, -s, s), p.y + randInt(rng, -s, s));
        cv::fillConvexPoly(img, poly, vividColour(rng), cv::LINE_AA);
      }
    }
  }
  // Title block in a contrasting band at the top.
  const int band = size.height / 6;
  cv::rectangle(img, cv::Rect(0, 0, size.width, band), randColour(rng, 0, 60), cv::FILLED);
  writeLine(
      rng, img, size.width / 20, size.width - size.width / 20, band * 3 / 4,
      kFonts[randInt(rng, 0, 3)], band * 0.5, cv::Scalar(245, 245, 245));
  return img;
}

cv::Mat makeCheckerboard(mrpt::random::CRandomGenerator& rng, cv::Size size, int cellPx)
{
  const cv::Scalar a = randColour(rng, 200, 255), b = randColour(rng, 0, 60);
  cv::Mat img(size, CV_8UC3, a);
  cellPx = std::max(1, cellPx);
  for (int r = 0; r * cellPx < size.height; ++r)
    for (int c = 0; c * cellPx < size.width; ++c)
      if ((r + c) % 2)
        cv::rectangle(img, cv::Rect(c * cellPx, r * cellPx, cellPx, cellPx), b, cv::FILLED);
  return img;
}

cv::Mat makeWoodTexture(mrpt::random::CRandomGenerator& rng, cv::Size size, int plankWidthPx)
{
  // Grain: noise stretched along the planks (image rows), one tint per plank.
  cv::Mat grain =
      makeNoiseTexture(rng, cv::Size(size.width, size.height / 8 + 1), {128, 128, 128}, 60, 2);
  cv::Mat img(size, CV_8UC3);
  plankWidthPx = std::max(2, plankWidthPx);
  const cv::Scalar wood(randInt(rng, 45, 70), randInt(rng, 85, 110), randInt(rng, 125, 160));
  for (int c0 = 0; c0 < size.width; c0 += plankWidthPx)
  {
    const double shade = rng.drawUniform(0.8, 1.15);  // planks differ a little
    const cv::Scalar tint = wood * shade;
    const int seam = randInt(rng, 0, size.height);
    for (int r = 0; r < size.height; ++r)
    {
      auto* o = img.ptr<cv::Vec3b>(r);
      for (int c = c0; c < std::min(size.width, c0 + plankWidthPx); ++c)
      {
        const double g = grain.at<cv::Vec3b>(r / 8, c)[0] - 128.0;  // streaks along the plank
        const bool edge = c == c0 || r == seam;
        for (int k = 0; k < 3; ++k)
          o[c][k] = cv::saturate_cast<uchar>(edge ? tint[k] * 0.45 : tint[k] + 0.35 * g);
      }
    }
  }
  return img;
}

void pasteTexture(cv::Mat& dst, const cv::Mat& patch, cv::Point topLeft)
{
  const cv::Rect target = cv::Rect(topLeft, patch.size()) & cv::Rect(0, 0, dst.cols, dst.rows);
  if (target.empty())
    return;
  patch(cv::Rect(target.tl() - topLeft, target.size())).copyTo(dst(target));
}
}  // namespace roislam::sim
