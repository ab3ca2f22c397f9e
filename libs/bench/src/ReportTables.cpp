#include "ReportTables.h"

#include <mrpt/system/string_utils.h>
#include <roislam/bench/CReportWriter.h>

#include <iomanip>
#include <sstream>

namespace roislam::bench::report
{
namespace
{
int modeRank(const std::string& mode)
{
  if (mode == "traditional")
    return 0;
  if (mode == "roi_small")
    return 1;
  if (mode == "roi_big")
    return 2;
  return 3;
}
}  // namespace

const std::vector<std::string> kFeatures{"surf", "sift", "orb"};

std::string num(double v, int decimals)
{
  std::ostringstream ss;
  ss << std::fixed << std::setprecision(decimals) << v;
  return ss.str();
}

std::string optNum(const std::optional<double>& v, int decimals)
{
  return v ? num(*v, decimals) : "n/a";
}

std::vector<std::string> featuresOf(const std::vector<const TRunRecord*>& recs)
{
  std::vector<std::string> out;
  for (const auto& f : kFeatures)
    for (const auto* r : recs)
      if (r->run.feature == f)
      {
        out.push_back(f);
        break;
      }
  return out;
}

std::vector<std::string> versionKeys(const std::vector<const TRunRecord*>& recs)
{
  auto keys = distinct(recs, [](const TRunRecord& r) { return r.run.versionKey(); });
  std::stable_sort(
      keys.begin(), keys.end(),
      [](const std::string& a, const std::string& b)
      { return modeRank(a.substr(0, a.find('/'))) < modeRank(b.substr(0, b.find('/'))); });
  return keys;
}

void featureHeader(
    std::ostream& md, const std::string& first, const std::vector<std::string>& feats,
    const std::string& refLabel)
{
  md << "| " << first << " |";
  for (const auto& f : feats)
    md << " " << mrpt::system::upperCase(f) << " | " << mrpt::system::upperCase(f) << " "
       << refLabel << " |";
  md << "\n|---|";
  for (std::size_t k = 0; k < feats.size(); ++k)
    md << "---|---|";
  md << "\n";
}

std::string labelOf(const std::vector<const TRunRecord*>& recs, const std::string& vk)
{
  for (const auto* r : recs)
    if (r->run.versionKey() == vk)
      return CReportWriter::versionLabel(*r);
  return vk;
}

TCell cellFor(
    const std::vector<const TRunRecord*>& recs, const std::string& vk, const std::string& f,
    const TGetter& get)
{
  TCell c;
  for (const auto* r : recs)
  {
    if (r->run.versionKey() != vk || r->run.feature != f)
      continue;
    ++c.total;
    if (!r->ok)
    {
      ++c.failed;
      continue;
    }
    if (auto v = get(*r))
      c.values.push_back(*v);
    else
      ++c.missingValue;
  }
  return c;
}

std::string renderCell(const TCell& c, int decimals, bool withStd)
{
  if (c.total == 0)
    return "—";
  if (c.values.empty())
  {
    if (c.failed == c.total)
      return "FAILED (" + std::to_string(c.failed) + "/" + std::to_string(c.total) + ")";
    return "n/a";
  }
  const auto ms = *meanStd(c.values);
  std::string s = num(ms.mean, decimals);
  if (withStd && ms.n > 1)
    s += " ± " + num(ms.std, decimals);
  std::string note = "n=" + std::to_string(ms.n);
  if (c.failed)
    note += ", " + std::to_string(c.failed) + " failed";
  return s + " (" + note + ")";
}

TGetter getter(const std::string& key)
{
  return [key](const TRunRecord& r) { return r.number(key); };
}

double durationOf(const TRunRecord& r)
{
  if (auto w = r.number("wall_s"))
    return *w;
  if (auto d = r.number("duration_s"))
    return *d;
  return r.wallS;
}

std::string oneLine(std::string s)
{
  for (char& c : s)
    if (c == '|' || c == '\n')
      c = ' ';
  return s;
}
}  // namespace roislam::bench::report
