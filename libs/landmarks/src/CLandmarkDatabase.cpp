#include "roislam/landmarks/CLandmarkDatabase.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "IniRead.h"

namespace roislam::landmarks
{
IMPLEMENTS_SERIALIZABLE(CLandmarkDatabase, CSerializable, roislam::landmarks)

namespace
{
// Lets generic MRPT readers (e.g. a polymorphic archive read) create our classes.
const bool g_registered = []
{
  mrpt::rtti::registerClass(CLASS_ID(CLandmark));
  mrpt::rtti::registerClass(CLASS_ID(CLandmarkDatabase));
  return true;
}();

matching::CFeatureMatcher::TOptions voteOptions(matching::CFeatureMatcher::TOptions o)
{
  // Plain nearest neighbour: a ratio test would discard exactly the features
  // shared by similar landmarks, which are the ones that should vote.
  o.ratio = 1.0;
  // The vote searches all stored descriptors (grows with the database):
  // approximate search pays off there even when brute force is faster for
  // ROI-sized sets.
  o.matcher = matching::EMatcherType::FLANN;
  o.cross_check = false;
  return o;
}
}  // namespace

void CLandmarkDatabase::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  max_candidates = detail::readInt(c, s, "max_candidates", max_candidates);
  prefilter_radius = detail::readDouble(c, s, "prefilter_radius", prefilter_radius);
  min_votes = detail::readInt(c, s, "min_votes", min_votes);
  min_overlap = detail::readDouble(c, s, "min_overlap", min_overlap);
  rigid_threshold = detail::readDouble(c, s, "rigid_threshold", rigid_threshold);
  min_rigid_inliers = detail::readInt(c, s, "min_rigid_inliers", min_rigid_inliers);
  min_rigid_fraction = detail::readDouble(c, s, "min_rigid_fraction", min_rigid_fraction);
  detail::require(rigid_threshold > 0, s, "rigid_threshold", rigid_threshold, "> 0");
  detail::require(min_rigid_inliers >= 3, s, "min_rigid_inliers", min_rigid_inliers, ">= 3");
  detail::require(
      min_rigid_fraction >= 0 && min_rigid_fraction <= 1, s, "min_rigid_fraction",
      min_rigid_fraction, "in [0, 1]");
  detail::require(max_candidates >= 0, s, "max_candidates", max_candidates, ">= 0");
  detail::require(prefilter_radius >= 0, s, "prefilter_radius", prefilter_radius, ">= 0");
  detail::require(min_votes >= 0, s, "min_votes", min_votes, ">= 0");
  detail::require(min_overlap >= 0 && min_overlap <= 1, s, "min_overlap", min_overlap, "in [0, 1]");
}

void CLandmarkDatabase::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "max_candidates", max_candidates);
  c.write(s, "prefilter_radius", prefilter_radius);
  c.write(s, "min_votes", min_votes);
  c.write(s, "min_overlap", min_overlap);
  c.write(s, "rigid_threshold", rigid_threshold);
  c.write(s, "min_rigid_inliers", min_rigid_inliers);
  c.write(s, "min_rigid_fraction", min_rigid_fraction);
}

CLandmarkDatabase::CLandmarkDatabase()
    : CLandmarkDatabase(
          TOptions(), matching::CFeatureMatcher::TOptions(),
          matching::CHomographyLocator::TOptions())
{
}

CLandmarkDatabase::CLandmarkDatabase(
    const TOptions& options, const matching::CFeatureMatcher::TOptions& matcherOptions,
    const matching::CHomographyLocator::TOptions& locatorOptions)
    : m_options(options),
      m_matcher(matcherOptions),
      m_voteMatcher(voteOptions(matcherOptions)),
      m_locator(locatorOptions)
{
  (void)g_registered;
}

const CLandmark& CLandmarkDatabase::landmark(int32_t id) const
{
  if (id < 0 || static_cast<std::size_t>(id) >= m_landmarks.size())
    throw std::out_of_range("landmark id " + std::to_string(id) + " not in the database");
  return m_landmarks[id];
}

void CLandmarkDatabase::clear()
{
  m_landmarks.clear();
  m_vote.reset();
}

int32_t CLandmarkDatabase::add(CLandmark landmark)
{
  if (!m_landmarks.empty() && landmark.features.type != m_landmarks.front().features.type)
    throw std::invalid_argument(
        "landmark database holds " + features::toString(m_landmarks.front().features.type) +
        " features; cannot add " + features::toString(landmark.features.type));
  landmark.id = static_cast<int32_t>(m_landmarks.size());
  m_landmarks.push_back(std::move(landmark));
  m_vote.reset();
  return m_landmarks.back().id;
}

void CLandmarkDatabase::addSighting(int32_t id, const TLandmarkSighting& sighting)
{
  landmark(id);  // range check
  m_landmarks[id].sightings.push_back(sighting);
}

std::shared_ptr<const CLandmarkDatabase::TVoteIndex> CLandmarkDatabase::voteIndex() const
{
  std::lock_guard<std::mutex> lock(*m_voteMutex);
  if (m_vote)
    return m_vote;
  // The index needs only the stacked descriptors (it keeps a reference).
  auto vote = std::make_shared<TVoteIndex>();
  features::TFeatureSet all;
  std::vector<cv::Mat> rows;
  for (const auto& lm : m_landmarks)
  {
    if (lm.features.empty())
      continue;
    all.type = lm.features.type;
    vote->owner.insert(vote->owner.end(), lm.features.size(), lm.id);
    rows.push_back(lm.features.descriptors);
  }
  if (!rows.empty())
    cv::vconcat(rows, all.descriptors);
  vote->index = std::make_shared<matching::CFeatureIndex>(m_voteMatcher.options(), all);
  m_vote = vote;
  return m_vote;
}

std::vector<int32_t> CLandmarkDatabase::candidates(
    const features::TFeatureSet& roiFeatures,
    const std::optional<mrpt::math::TPoint3D>& worldPosition) const
{
  std::vector<int32_t> pool;
  for (const auto& lm : m_landmarks)
  {
    if (worldPosition && lm.hasPositionWorld && m_options.prefilter_radius > 0 &&
        (lm.positionWorld - *worldPosition).norm() > m_options.prefilter_radius)
      continue;
    pool.push_back(lm.id);
  }
  const std::size_t maxCandidates = static_cast<std::size_t>(m_options.max_candidates);
  if (maxCandidates == 0 || pool.size() <= maxCandidates)
    return pool;

  const auto vote = voteIndex();
  std::vector<int> votes(m_landmarks.size(), 0);
  for (const auto& m : vote->index->match(roiFeatures))
    ++votes[vote->owner[m.trainIdx]];
  std::stable_sort(
      pool.begin(), pool.end(), [&](int32_t a, int32_t b) { return votes[a] > votes[b]; });
  pool.resize(maxCandidates);
  pool.erase(
      std::remove_if(
          pool.begin(), pool.end(), [&](int32_t id) { return votes[id] < m_options.min_votes; }),
      pool.end());
  return pool;
}

CLandmarkDatabase::TQueryResult CLandmarkDatabase::query(
    const features::TFeatureSet& roiFeatures, const cv::Rect& roiBox, const cv::Size& imageSize,
    const std::vector<mrpt::math::TPoint3D>& roiPoints,
    const std::optional<mrpt::math::TPoint3D>& worldPosition) const
{
  const bool haveRoiPoints = roiPoints.size() == roiFeatures.size();
  TQueryResult best;
  if (roiFeatures.empty() || m_landmarks.empty())
    return best;
  if (roiFeatures.type != m_landmarks.front().features.type)
    throw std::invalid_argument(
        "landmark database holds " + features::toString(m_landmarks.front().features.type) +
        " features; query has " + features::toString(roiFeatures.type));

  const auto ids = candidates(roiFeatures, worldPosition);
  best.candidates = static_cast<int>(ids.size());
  // One search structure over the ROI for all candidates.
  const matching::CFeatureIndex roiIndex(m_matcher.options(), roiFeatures);
  for (int32_t id : ids)
  {
    const CLandmark& lm = m_landmarks[id];
    if (lm.features.empty())
      continue;
    const auto matches = roiIndex.match(lm.features);
    const auto located = m_locator.locate(lm.features, lm.box, roiFeatures, imageSize, matches);
    if (!located)
      continue;
    const double inter = (located->box & roiBox).area();
    const double uni = located->box.area() + roiBox.area() - inter;
    const double overlap = uni > 0 ? inter / uni : 0;
    if (overlap < m_options.min_overlap)
      continue;
    int inliers = static_cast<int>(located->inliers.size());

    // 3-D check: the inliers' first-sight and current points must be related
    // by one rigid motion (a similar texture elsewhere is not).
    std::optional<TRigidFit> rigid;
    if (haveRoiPoints && lm.featurePoints.size() == lm.features.size())
    {
      std::vector<mrpt::math::TPoint3D> now, then;
      for (const auto& m : located->inliers)
      {
        now.push_back(roiPoints[m.trainIdx]);
        then.push_back(lm.featurePoints[m.queryIdx]);
      }
      int pairs = 0;
      for (std::size_t i = 0; i < now.size(); ++i)
        pairs += isValidPoint(now[i]) && isValidPoint(then[i]);
      if (pairs >= m_options.min_rigid_inliers)
      {
        rigid = fitRigid(now, then, m_options.rigid_threshold);
        if (!rigid || rigid->inliers < m_options.min_rigid_inliers ||
            rigid->inliers < m_options.min_rigid_fraction * rigid->pairs)
          continue;
        inliers = rigid->inliers;
      }
    }
    if (inliers > best.inliers)
    {
      best.landmarkId = id;
      best.inliers = inliers;
      best.matches = located->numMatches;
      best.falseMatches = located->falseMatches;
      best.locatedBox = located->box;
      best.overlap = overlap;
      best.inlierMatches = located->inliers;
      best.rigid = rigid;
    }
  }
  return best;
}

uint8_t CLandmarkDatabase::serializeGetVersion() const
{
  return 0;
}

void CLandmarkDatabase::serializeTo(mrpt::serialization::CArchive& out) const
{
  out << static_cast<uint64_t>(m_landmarks.size());
  for (const auto& lm : m_landmarks)
    out << lm;
}

void CLandmarkDatabase::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version)
{
  switch (version)
  {
    case 0:
    {
      uint64_t n = 0;
      in >> n;
      if (n > (1u << 24))
        throw std::runtime_error("corrupt landmark count in archive");
      std::vector<CLandmark> loaded(n);
      for (auto& lm : loaded)
        in >> lm;
      for (std::size_t i = 0; i < loaded.size(); ++i)
        if (loaded[i].id != static_cast<int32_t>(i))
          throw std::runtime_error("landmark ids in archive are not 0..n-1");
      m_landmarks = std::move(loaded);
      m_vote.reset();
      break;
    }
    default:
      MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
  }
}

void CLandmarkDatabase::save(const std::string& file) const
{
  const std::string tmp = file + ".tmp";
  {
    mrpt::io::CFileGZOutputStream f;
    if (!f.open(tmp))
      throw std::runtime_error(file + ": cannot write");
    try
    {
      auto ar = mrpt::serialization::archiveFrom(f);
      ar << *this;
    }
    catch (const std::exception& e)
    {
      f.close();
      std::remove(tmp.c_str());
      throw std::runtime_error(file + ": cannot write: " + e.what());
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec)
    throw std::runtime_error(file + ": cannot write: " + ec.message());
}

void CLandmarkDatabase::load(const std::string& file)
{
  mrpt::io::CFileGZInputStream f;
  if (!std::filesystem::is_regular_file(file) || !f.open(file))
    throw std::runtime_error(file + ": cannot open");
  try
  {
    auto ar = mrpt::serialization::archiveFrom(f);
    ar >> *this;
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(file + ": not a landmark database: " + e.what());
  }
}
}  // namespace roislam::landmarks
