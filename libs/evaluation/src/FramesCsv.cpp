#include "roislam/evaluation/FramesCsv.h"

#include <roislam/common/IniRead.h>
#include <roislam/common/TextFiles.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace roislam::evaluation
{
namespace
{
/** Splits on ',' keeping empty fields (an empty "keyframe" cell). */
std::vector<std::string> fields(const std::string& line)
{
  std::vector<std::string> out;
  std::string f;
  std::istringstream in(line);
  while (std::getline(in, f, ','))
    out.push_back(f);
  if (!line.empty() && line.back() == ',')
    out.emplace_back();
  return out;
}
}  // namespace

TFrameTimes readFrameTimes(const std::string& framesCsv)
{
  std::istringstream text(common::readFile(framesCsv));
  std::string line;
  std::size_t lineNo = 0;
  const auto fail = [&](const std::string& what)
  { return std::runtime_error(framesCsv + ":" + std::to_string(lineNo) + ": " + what); };
  std::size_t timeCol = 0, keyCol = 0;
  {
    ++lineNo;
    if (!std::getline(text, line))
      throw std::runtime_error(framesCsv + ": no frames (empty file)");
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    const auto header = fields(line);
    const auto column = [&](const std::string& name)
    {
      const auto it = std::find(header.begin(), header.end(), name);
      if (it == header.end())
        throw fail("no '" + name + "' column (not a roi-graphslam frames.csv?)");
      return static_cast<std::size_t>(it - header.begin());
    };
    timeCol = column("timestamp");
    keyCol = column("keyframe");
  }
  TFrameTimes out;
  while (std::getline(text, line))
  {
    ++lineNo;
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.empty())
      continue;
    const auto f = fields(line);
    if (f.size() <= std::max(timeCol, keyCol))
      throw fail("too few fields");
    const auto t = common::parseDouble(f[timeCol]);
    if (!t || !std::isfinite(*t))
      throw fail("timestamp '" + f[timeCol] + "' is not a number");
    out.frames.push_back(*t);
    if (f[keyCol].empty())
      continue;
    const auto node = common::parseUnsigned(f[keyCol]);
    if (!node)
      throw fail("keyframe '" + f[keyCol] + "' is not a node number");
    if (!out.keyframes.emplace(*node, *t).second)
      throw fail("keyframe " + f[keyCol] + " named twice");
  }
  if (out.frames.empty())
    throw std::runtime_error(framesCsv + ": no frames");
  std::sort(out.frames.begin(), out.frames.end());
  return out;
}
}  // namespace roislam::evaluation
