/* Stage 1: the region of interest, i.e. the most highly detailed patch of a
 * colour image: Canny edges -> 3x3 morphology (erosions, then dilations) ->
 * the largest connected component's bounding box. Optionally verified by a
 * second detector on the hue channel (the dissertation's proposal, verify_hue
 * below). Called per frame by the landmark pipeline and the ROI modes of the
 * SLAM front end.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <roislam/roi/HueEdges.h>

#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace roislam::roi
{
struct TRoi
{
  cv::Rect box;
  /** Pixels of the connected component (<= box.area()). */
  int componentArea = 0;
};

/** Stage 1 with its verification: what each detector found. */
struct TRoiDetection
{
  /** The accepted ROI (the grey detector's, verified when verify_hue). */
  std::optional<TRoi> roi;
  /** The grey detector's ROI (accepted or not). */
  std::optional<TRoi> grey;
  /** verify_hue: the hue detector's ROI and its intersection over union
   *  with the grey one (0 when either is missing). */
  std::optional<TRoi> hue;
  double iou = 0;
  /** verify_hue found a grey ROI and rejected it. */
  bool rejectedByHue() const { return grey && !roi; }
};

class CRoiDetector
{
 public:
  /** Morphology convention. The dissertation treats edges as black foreground
   *  on a white background, so its "erosion" grows the edges and its
   *  "dilation" shrinks them. We keep its counts and that meaning: `erosions`
   *  = iterations that grow the edge pixels (OpenCV dilate on our white-edge
   *  mask), `dilations` = iterations that shrink them (OpenCV erode), applied
   *  in that order. Read literally on white edges, 6 erosions would delete
   *  every 1-px Canny edge and no ROI would ever exist. The "big" preset keeps
   *  the 6 edge-growing iterations and shrinks by only 2, so the merged patches
   *  stay bigger than "small" (6 / 7): measured on fr1/rpy, see README.
   *
   *  ini section (default "RoiDetector"):
   *  - preset            small|big|custom (default big); small = 6 erosions +
   *                      7 dilations, big = 6 erosions + 2 dilations;
   *                      custom uses the two keys below
   *  - erosions, dilations   int >= 0, only read with preset=custom
   *  - canny_low, canny_high double (default 250 / 300), aperture 3
   *  - min_area_fraction     double in [0,1): components smaller than this
   *                          fraction of the image are "no ROI" (default 0.002)
   *  - verify_hue            bool (default false): a second stage-1 detector
   *                          runs on the hue channel of the colour image
   *                          (OpenCV HSV; hue edges, HueEdges.h, then the
   *                          same morphology and largest component). The ROI
   *                          is accepted when the two boxes agree,
   *                          intersection over union >= hue_min_iou;
   *                          otherwise, and when the hue detector finds no
   *                          ROI (a grey scene), the frame has no ROI, as if
   *                          stage 1 had found none. The accepted box is the
   *                          grey detector's. Needs the colour image
   *                          (detect() throws on a grey one).
   *  - hue_canny_low_deg, hue_canny_high_deg  degrees, 0 < low <= high <= 180
   *                          (default 20 / 40): Canny thresholds as hue steps
   *                          between neighbouring pixels (hue is circular:
   *                          0 and 179 are 2 degrees apart, HueEdges.h)
   *  - hue_min_saturation, hue_min_value  in [0, 1] (default 0.25 / 0.2):
   *                          pixels below either have no reliable hue and
   *                          make no hue edge
   *  - hue_min_iou           in (0, 1] (default 0.5, the usual agreement
   *                          of two detections of one object)
   */
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    std::string preset = "big";
    int erosions = 6;
    int dilations = 2;
    double canny_low = 250;
    double canny_high = 300;
    double min_area_fraction = 0.002;
    bool verify_hue = false;
    double hue_canny_low_deg = 20;
    double hue_canny_high_deg = 40;
    double hue_min_saturation = 0.25;
    double hue_min_value = 0.2;
    double hue_min_iou = 0.5;

    THueEdgeParams hueParams() const;

    /** Sets preset and the matching erosion/dilation counts; throws on an unknown name. */
    void setPreset(const std::string& name);
    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };

  // Two constructors rather than a default argument: GCC rejects TOptions()
  // as a default argument inside the enclosing class.
  CRoiDetector();
  explicit CRoiDetector(const TOptions& options);

  /** The ROI of a grey (CV_8UC1) or BGR image, or nullopt when none.
   *  verify_hue needs a BGR image (std::invalid_argument otherwise). */
  std::optional<TRoi> detect(const cv::Mat& image) const;
  /** The same for a frame whose grey image the caller has already: grey
   *  (CV_8UC1) for the grey detector, bgr (CV_8UC3, may be empty without
   *  verify_hue) for the hue detector. */
  std::optional<TRoi> detect(const cv::Mat& grey, const cv::Mat& bgr) const;
  /** detect() with what each detector found. */
  TRoiDetection detectDetailed(const cv::Mat& grey, const cv::Mat& bgr) const;

  /** The binary foreground mask after morphology (for debugging/tests). */
  cv::Mat foregroundMask(const cv::Mat& image) const;
  /** The same for the hue detector (BGR image). */
  cv::Mat hueForegroundMask(const cv::Mat& bgr) const;

  const TOptions& options() const { return m_options; }

 private:
  /** Edge-growing then edge-shrinking iterations, in place. */
  void morphology(cv::Mat& edges) const;
  std::optional<TRoi> largestRoi(const cv::Mat& mask) const;

  TOptions m_options;
};
}  // namespace roislam::roi
