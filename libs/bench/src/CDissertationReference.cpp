#include "roislam/bench/CDissertationReference.h"

#include <roislam/bench/ProcessUtils.h>

#include <stdexcept>

namespace roislam::bench
{
CDissertationReference CDissertationReference::fromFile(const std::string& file)
{
  try
  {
    return CDissertationReference(nlohmann::json::parse(readFile(file)));
  }
  catch (const nlohmann::json::exception& e)
  {
    throw std::runtime_error(file + ": not valid JSON: " + e.what());
  }
}

const nlohmann::json* CDissertationReference::find(std::initializer_list<std::string> path) const
{
  const nlohmann::json* node = &m_data;
  for (const auto& key : path)
  {
    if (!node->is_object())
      return nullptr;
    const auto it = node->find(key);
    if (it == node->end())
      return nullptr;
    node = &*it;
  }
  return node;
}

std::optional<int> CDissertationReference::sequenceId(const std::string& folderName) const
{
  const auto* seqs = find({"sequences"});
  if (!seqs || !seqs->is_array())
    return std::nullopt;
  const std::string prefix = "rgbd_dataset_";
  for (const auto& s : *seqs)
  {
    const std::string tum = s.value("tum_name", "");
    if (tum.empty())
      continue;
    if (folderName == tum || (tum.rfind(prefix, 0) == 0 && folderName == tum.substr(prefix.size())))
      return s.value("id", 0);
  }
  return std::nullopt;
}

std::string CDissertationReference::sequenceShortName(int id) const
{
  const auto* seqs = find({"sequences"});
  if (seqs && seqs->is_array())
    for (const auto& s : *seqs)
      if (s.value("id", 0) == id)
        return s.value("short", "");
  return {};
}

std::optional<std::array<double, 3>> CDissertationReference::test1(
    int seqId, const std::string& feature) const
{
  const auto* v = find({"test1", "landmarks_fp_fn", std::to_string(seqId), feature});
  if (!v || !v->is_array() || v->size() != 3)
    return std::nullopt;
  return std::array<double, 3>{(*v)[0].get<double>(), (*v)[1].get<double>(), (*v)[2].get<double>()};
}

std::optional<std::array<double, 3>> CDissertationReference::test1Average(
    const std::string& feature) const
{
  const auto* all = find({"test1", "landmarks_fp_fn"});
  if (!all || !all->is_object())
    return std::nullopt;
  std::array<double, 3> sum{0, 0, 0};
  int n = 0;
  for (const auto& [id, perFeature] : all->items())
  {
    const auto v = test1(std::stoi(id), feature);
    if (!v)
      continue;
    for (int k = 0; k < 3; ++k)
      sum[k] += (*v)[k];
    ++n;
  }
  if (n == 0)
    return std::nullopt;
  for (auto& s : sum)
    s /= n;
  return sum;
}

namespace
{
std::optional<double> numberAt(const nlohmann::json* v)
{
  if (!v || !v->is_number())
    return std::nullopt;
  return v->get<double>();
}
}  // namespace

std::optional<double> CDissertationReference::test1TruePositiveRate(const std::string& f) const
{
  return numberAt(find({"test1", "true_positive_rate", f}));
}
std::optional<double> CDissertationReference::test1TrueNegativeRate(const std::string& f) const
{
  return numberAt(find({"test1", "true_negative_rate", f}));
}
std::optional<double> CDissertationReference::test1Fps(const std::string& f) const
{
  return numberAt(find({"test1", "fps", f}));
}

std::optional<std::pair<double, double>> CDissertationReference::ate(
    int test, const std::string& mode, const std::string& feature) const
{
  const nlohmann::json* v =
      test == 2 ? find({"test2", mode, "ate", feature}) : find({"test3", mode, "ate"});
  if (test == 3)
  {
    const auto* f = find({"test3", "feature"});
    if (f && f->is_string() && f->get<std::string>() != feature)
      return std::nullopt;
  }
  if (!v || !v->is_array() || v->size() != 2)
    return std::nullopt;
  return std::make_pair((*v)[0].get<double>(), (*v)[1].get<double>());
}

std::optional<double> CDissertationReference::scalar(
    int test, const std::string& mode, const std::string& feature, const std::string& metric) const
{
  if (test == 2)
    return numberAt(find({"test2", mode, metric, feature}));
  const auto* f = find({"test3", "feature"});
  if (f && f->is_string() && f->get<std::string>() != feature)
    return std::nullopt;
  return numberAt(find({"test3", mode, metric}));
}
}  // namespace roislam::bench
