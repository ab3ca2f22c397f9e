/* Every option of the ROI landmark pipeline, loaded from one ini file with
 * one section per class, with strict key checking. Used by the roi-landmarks
 * app and by the observation processor.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/features/CFeatureExtractor.h>
#include <roislam/kfslam/TKfSlamOptions.h>
#include <roislam/landmarks/CLandmarkDatabase.h>
#include <roislam/landmarks/CLandmarkScorer.h>
#include <roislam/landmarks/TObservationOptions.h>
#include <roislam/matching/CFeatureMatcher.h>
#include <roislam/matching/CHomographyLocator.h>
#include <roislam/roi/CRoiDetector.h>

#include <string>

namespace roislam::landmarks
{
/** ini section "RoiLandmarks" (the tracker's own keys):
 *  - min_depth   metres > 0: shorter depth readings are ignored (default 0.1)
 *  - max_depth   metres > min_depth: longer readings are ignored (default 8.0)
 *  - confirm     bool: a ROI must be re-found in the previous frame before it
 *                is matched against the database, as in the dissertation
 *                (default true)
 *  - max_position_jump  metres >= 0: a recall whose ROI position (median
 *                feature point) is farther than this from the recalled
 *                landmark's point (as located in the frame) is stored as a new
 *                landmark instead: the ROI box then covers a different extent
 *                of the scene. 0 = off (default 0)
 */
struct TTrackerOptions : public mrpt::config::CLoadableOptions
{
  double min_depth = 0.1;
  double max_depth = 8.0;
  bool confirm = true;
  double max_position_jump = 0;

  void loadFromConfigFile(
      const mrpt::config::CConfigFileBase& source, const std::string& section) override;
  void saveToConfigFile(
      mrpt::config::CConfigFileBase& target, const std::string& section) const override;
};

/** The whole configuration of roi-landmarks. */
struct TPipelineOptions
{
  roi::CRoiDetector::TOptions roi;                 // [RoiDetector]
  features::CFeatureExtractor::TOptions features;  // [FeatureExtractor]
  matching::CFeatureMatcher::TOptions matcher;     // [FeatureMatcher]
  matching::CHomographyLocator::TOptions locator;  // [HomographyLocator]
  CLandmarkDatabase::TOptions database;            // [LandmarkDatabase]
  TTrackerOptions tracker;                         // [RoiLandmarks]
  CLandmarkScorer::TOptions scoring;               // [LandmarkScoring]
  TObservationOptions observations;                // [ObservationProcessor]
  kfslam::TKfSlamOptions kfSlam;                   // [KfSlam] (roi-landmarks --kf-slam)

  /** Loads every section present (absent sections keep defaults), after
   *  checking that each of these sections holds only known keys;
   *  fileLabel names the file in error messages. */
  void load(const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel);
  /** Reads an ini file; throws "ini <file>: cannot open" when unreadable. */
  void loadFromFile(const std::string& file);
  void save(mrpt::config::CConfigFileBase& cfg) const;
};
}  // namespace roislam::landmarks
