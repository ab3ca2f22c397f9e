/* feature-bench's engine: measures SIFT, SURF (roislam's CSurf), ORB and AKAZE
 * on real frames warped by known homographies (rotation, scale, blur,
 * brightness): keypoints per frame, milliseconds per frame, repeatability and
 * matching score (BenchMetrics.h). Called by apps/feature-bench and its tests.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <roislam/featurebench/BenchMetrics.h>

#include <map>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <optional>
#include <string>
#include <vector>

namespace roislam::featurebench
{
class CFeatureBench
{
 public:
  /** ini section (default "FeatureBench"):
   *  - input          TUM folder with rgb.txt (required, no default)
   *  - frames         int >= 1: frames used, evenly spaced over the sequence (default 15)
   *  - max_features   int >= 0: the same cap for every extractor, strongest
   *                   kept; 0 = uncapped (ORB then asks for 100000) (default 1000)
   *  - extractors     comma list of sift,surf,orb,akaze (default all four)
   *  - transforms     comma list of rot15,rot30,rot45,scale1.2,scale1.5,scale2.0,
   *                   blur,brightness (default all)
   *  - blur_sigma     double > 0: Gaussian blur sigma, pixels (default 2.0)
   *  - brightness_offset  int: added grey level, saturating (default 40)
   *  - pixel_tolerance    double > 0: pixel criterion, correspondence
   *                       distance, pixels (default 2.5)
   *  - border_margin      double >= 0: common-part margin, pixels (default 8)
   *  - max_overlap_error  double in (0, 1]: overlap criterion, largest region
   *                       overlap error (default 0.4, IJCV 2005)
   *  - region_scale       double > 0: overlap criterion, region radius in
   *                       units of the keypoint's blob scale (default 3)
   * Both criteria (BenchMetrics.h) are evaluated in every run and reported.
   * For the overlap criterion every extractor's keypoint.size is converted to
   * a "blob scale" by calibration: the size it reports for an isolated
   * Gaussian blob of sigma 8 px (bright and dark) is taken as sigma 8, so the
   * regions of all extractors are the same multiple of the blob they sit on.
   * An extractor that detects no such blob (ORB: FAST corners) falls back to
   * the OpenCV meaning of size, the diameter of the described neighbourhood:
   * region radius = size / 2.
   */
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    std::string input;
    int frames = 15;
    int max_features = 1000;
    std::vector<std::string> extractors{"sift", "surf", "orb", "akaze"};
    std::vector<std::string> transforms{"rot15",    "rot30",    "rot45", "scale1.2",
                                        "scale1.5", "scale2.0", "blur",  "brightness"};
    double blur_sigma = 2.0;
    int brightness_offset = 40;
    double pixel_tolerance = 2.5;
    double border_margin = 8.0;
    double max_overlap_error = 0.4;
    double region_scale = 3.0;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
    /** Throws std::invalid_argument naming the key of the first bad value. */
    void validate(const std::string& section = "FeatureBench") const;
  };

  /** One extractor under one transformation, averaged over the frames. */
  struct TRow
  {
    std::string extractor, transform;
    std::size_t frames = 0;
    /** Mean keypoints per original frame. */
    double keypointsPerFrame = 0;
    /** Mean detect+describe time per image (originals and warped images). */
    double msPerFrame = 0;
    /** Means over frames of the per-frame values (BenchMetrics.h), pixel
     *  criterion. */
    double repeatability = 0, matchingScore = 0;
    double correspondencesPerFrame = 0, commonPerFrame = 0;
    /** The same under the overlap-error criterion. */
    double repeatabilityOverlap = 0, matchingScoreOverlap = 0;
    double correspondencesOverlapPerFrame = 0;
    /** Keypoint noise per image axis at the finest detection scale (px, 1
     *  sigma; BenchMetrics.h localisationSigma) over all the frames' correct
     *  matches (pixel criterion); 0 without any, and for "none". */
    double localisationSigmaPx = 0;
    /** The finest-scale correct matches it was measured on. */
    std::size_t localisationMatches = 0;
  };

  struct TResult
  {
    std::string input;
    int maxFeatures = 0;
    std::size_t frames = 0;
    cv::Size imageSize;
    std::vector<TRow> rows;
    /** Per extractor: overlap-criterion region radius per unit keypoint.size,
     *  and whether it came from the blob calibration (else size / 2). */
    std::map<std::string, double> regionRadiusPerSize;
    std::map<std::string, bool> regionCalibrated;
    /** Row of (extractor, transform), or nullptr. */
    const TRow* find(const std::string& extractor, const std::string& transform) const;
  };

  /** Validates the options (throws std::invalid_argument naming the key). */
  explicit CFeatureBench(const TOptions& options);

  /** Reads the frames (throws std::runtime_error naming rgb.txt and its line,
   *  or the image that cannot be read) and runs every extractor. */
  TResult run() const;

  /** Homography of a named transformation for an image of the given size
   *  (identity for blur and brightness); throws std::invalid_argument. */
  static cv::Matx33d homography(const std::string& transform, const cv::Size& size);

  /** keypoint.size the extractor reports for a Gaussian blob of sigma 8 px
   *  divided by 8 (mean of a bright and a dark blob), or std::nullopt when it
   *  finds neither blob. */
  static std::optional<double> sizePerBlobSigma(cv::Feature2D& extractor);

  /** Fixed-width text table, one line per row. */
  static std::string toTable(const TResult& result);
  /** JSON: {"input", "max_features", "frames", "results": [one object per row]}. */
  static std::string toJson(const TResult& result);

  /** The colour images listed in <dir>/rgb.txt, n of them evenly spaced. */
  static std::vector<std::string> selectFrames(const std::string& dir, int n);

  /** "a, b,c" -> {"a","b","c"} (for the extractors / transforms lists). */
  static std::vector<std::string> parseList(const std::string& commaList);

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::featurebench
