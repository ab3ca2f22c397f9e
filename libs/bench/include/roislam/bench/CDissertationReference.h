/* The dissertation's reported figures (share/roi-bench/dissertation.json,
 * transcribed from MISSION.md) with typed look-ups, so the report can put
 * them next to ours. A sequence maps to the dissertation's numbering only when
 * its folder name is the TUM sequence name (rgbd_dataset_ prefix optional).
 * Used by CReportWriter.
 */
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

namespace roislam::bench
{
class CDissertationReference
{
 public:
  /** Empty reference: every look-up returns nullopt. */
  CDissertationReference() = default;
  explicit CDissertationReference(nlohmann::json data) : m_data(std::move(data)) {}
  /** Throws std::runtime_error naming the file when unreadable or not JSON. */
  static CDissertationReference fromFile(const std::string& file);

  /** 1..8 for the dissertation's sequences, by folder name. */
  std::optional<int> sequenceId(const std::string& folderName) const;
  /** "fr1/xyz" etc. */
  std::string sequenceShortName(int id) const;

  /** Test 1: landmarks, false positives, false negatives. */
  std::optional<std::array<double, 3>> test1(int seqId, const std::string& feature) const;
  /** Test 1: the same averaged over the dissertation's sequences. */
  std::optional<std::array<double, 3>> test1Average(const std::string& feature) const;
  std::optional<double> test1TruePositiveRate(const std::string& feature) const;
  std::optional<double> test1TrueNegativeRate(const std::string& feature) const;
  std::optional<double> test1Fps(const std::string& feature) const;

  /** Test 2 (test = 2) or 3 (feature ignored): ATE mean and std, metres. */
  std::optional<std::pair<double, double>> ate(
      int test, const std::string& mode, const std::string& feature) const;
  /** metric: "rpe_trans" (m), "rpe_rot_deg" (deg) or "duration_min" (min). */
  std::optional<double> scalar(
      int test, const std::string& mode, const std::string& feature,
      const std::string& metric) const;

  const nlohmann::json& data() const { return m_data; }

 private:
  nlohmann::json m_data;
  const nlohmann::json* find(std::initializer_list<std::string> path) const;
};
}  // namespace roislam::bench
