#include "roislam/bench/TVariant.h"

#include <mrpt/system/string_utils.h>
#include <roislam/common/ErrorText.h>

#include <cctype>
#include <sstream>
#include <stdexcept>

namespace roislam::bench
{
namespace
{
// Lines of raw ini text end in '\r' in CRLF files, which mrpt::system::trim
// (blanks and tabs) keeps.
std::string trim(const std::string& s)
{
  return mrpt::system::trim(!s.empty() && s.back() == '\r' ? s.substr(0, s.size() - 1) : s);
}
}  // namespace

TVariant TVariant::parse(const std::string& spec)
{
  const auto bad = [&](const std::string& why)
  {
    return std::invalid_argument(
        "variant '" + common::printableExcerpt(spec, 80) +
        "': " + common::printableExcerpt(why, 200) + " (expected name:Section.key=value[,...])");
  };
  const auto colon = spec.find(':');
  if (colon == std::string::npos || colon == 0)
    throw bad("missing name");
  TVariant v;
  v.name = spec.substr(0, colon);
  for (char c : v.name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_')
      throw bad("name may only contain letters, digits and '_'");
  v.label = spec;
  std::stringstream ss(spec.substr(colon + 1));
  std::string item;
  while (std::getline(ss, item, ','))
  {
    const auto dot = item.find('.');
    const auto eq = item.find('=');
    if (dot == std::string::npos || eq == std::string::npos || dot > eq || dot == 0 ||
        eq == dot + 1)
      throw bad("bad override '" + item + "'");
    v.overrides.push_back(
        {trim(item.substr(0, dot)), trim(item.substr(dot + 1, eq - dot - 1)),
         trim(item.substr(eq + 1))});
  }
  if (v.overrides.empty())
    throw bad("no override");
  return v;
}

std::vector<TVariant> defaultVariants()
{
  return {// The dissertation: no fallback, and its N features taken in the ROI.
          {"strict",
           "strict ROI, no fallback (dissertation's behaviour)",
           {{"FrontEnd", "strict_roi", "true"}, {"FrontEnd", "roi_feature_cap", "roi"}}},
          {"fallback",
           "ROI with fallback, shipped configs: the keyframe's anchors followed by optical flow, "
           "the ROI described when they are weak (ours)",
           {{"FrontEnd", "strict_roi", "false"}, {"FrontEnd", "roi_feature_cap", "image"}}},
          {"roicap",
           "ROI with fallback, whole image described, N features in the ROI (ours)",
           {{"FrontEnd", "strict_roi", "false"},
            {"FrontEnd", "roi_feature_cap", "roi"},
            {"FrontEnd", "roi_extraction", "image"}}},
          // Issue 15: stage 2 on the tracking region only, the rest of the
          // image at half resolution when a frame needs it.
          {"region",
           "ROI with fallback, features described in the tracking region only (ours)",
           {{"FrontEnd", "strict_roi", "false"},
            {"FrontEnd", "roi_feature_cap", "image"},
            {"FrontEnd", "roi_extraction", "region"},
            {"FrontEnd", "roi_extension_scale", "0.5"}}},
          // Issue 15 before the shipped configs' flow (stop 30): every frame
          // describes the whole image, the ROI selects its subset.
          {"image",
           "ROI with fallback, whole image described on every frame (ours, before flow)",
           {{"FrontEnd", "strict_roi", "false"},
            {"FrontEnd", "roi_feature_cap", "image"},
            {"FrontEnd", "roi_extraction", "image"}}}};
}

std::vector<TVariant> defaultTest1Variants()
{
  return {
      {"hue",
       "hue-verified ROI ([RoiDetector] verify_hue = true)",
       {{"RoiDetector", "verify_hue", "true"}}}};
}

std::string applyIniOverrides(const std::string& iniText, const std::vector<TIniOverride>& ov)
{
  std::vector<std::string> lines;
  {
    std::stringstream ss(iniText);
    std::string l;
    while (std::getline(ss, l))
      lines.push_back(l);
  }
  for (const auto& o : ov)
  {
    std::string section;
    bool done = false;
    long lastLineOfSection = -1;
    for (std::size_t i = 0; i < lines.size() && !done; ++i)
    {
      const std::string t = trim(lines[i]);
      if (!t.empty() && t.front() == '[' && t.back() == ']')
      {
        section = trim(t.substr(1, t.size() - 2));
        if (section == o.section)
          lastLineOfSection = static_cast<long>(i);
        continue;
      }
      if (section != o.section)
        continue;
      if (!t.empty() && t[0] != ';' && t[0] != '#')
        lastLineOfSection = static_cast<long>(i);
      const auto eq = t.find('=');
      if (eq != std::string::npos && t[0] != ';' && t[0] != '#' && trim(t.substr(0, eq)) == o.key)
      {
        lines[i] = o.key + " = " + o.value;
        done = true;
      }
    }
    if (done)
      continue;
    if (lastLineOfSection >= 0)
      lines.insert(lines.begin() + lastLineOfSection + 1, o.key + " = " + o.value);
    else
    {
      lines.push_back("[" + o.section + "]");
      lines.push_back(o.key + " = " + o.value);
    }
  }
  std::string out;
  for (const auto& l : lines)
    out += l + "\n";
  return out;
}
}  // namespace roislam::bench
