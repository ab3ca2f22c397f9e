/* feature-bench engine (see CFeatureBench.h). */
#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/StringLists.h>
#include <roislam/featurebench/CFeatureBench.h>
#include <roislam/features/CSurf.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

namespace roislam::featurebench
{
using common::joinList;
using common::splitList;

namespace
{
const std::vector<std::string> kExtractors{"sift", "surf", "orb", "akaze"};
// rot5: the small turn between two frames of a sequence, where the keypoint
// noise the front end weighs its edges with is measured (loc_px).
const std::vector<std::string> kTransforms{"none",  "rot5",      "rot15",    "rot30",
                                           "rot45", "scale1.2",  "scale1.5", "scale2.0",
                                           "blur",  "brightness"};

/** One extractor with the common cap applied the same way for all: through
 *  the extractor's own parameter where it has one (strongest kept), else by
 *  keeping the strongest responses before description (AKAZE). */
struct TExtractor
{
  std::string name;
  cv::Ptr<cv::Feature2D> feature;
  int cap = 0;
  bool capAfterDetect = false;

  void run(const cv::Mat& img, std::vector<cv::KeyPoint>& kps, cv::Mat& desc) const
  {
    if (!capAfterDetect)
    {
      feature->detectAndCompute(img, cv::noArray(), kps, desc);
      return;
    }
    feature->detect(img, kps);
    if (cap > 0)
      cv::KeyPointsFilter::retainBest(kps, cap);
    feature->compute(img, kps, desc);
  }
};

TExtractor makeExtractor(const std::string& name, int cap)
{
  TExtractor e;
  e.name = name;
  e.cap = cap;
  if (name == "sift")
    e.feature = cv::SIFT::create(cap);
  else if (name == "surf")
  {
    features::CSurf::TParams p;
    p.maxFeatures = cap;
    e.feature = features::CSurf::create(p);
  }
  else if (name == "orb")
    e.feature = cv::ORB::create(cap > 0 ? cap : 100000);
  else if (name == "akaze")
  {
    e.feature = cv::AKAZE::create();
    e.capAfterDetect = true;
  }
  else
    throw std::invalid_argument("unknown extractor '" + name + "'");
  return e;
}

cv::Mat applyTransform(
    const cv::Mat& img, const std::string& t, const cv::Matx33d& H,
    const CFeatureBench::TOptions& o)
{
  cv::Mat out;
  if (t == "blur")
    cv::GaussianBlur(img, out, cv::Size(0, 0), o.blur_sigma);
  else if (t == "brightness")
    img.convertTo(out, -1, 1.0, o.brightness_offset);
  else if (t == "none")
    out = img;
  else
    cv::warpPerspective(
        img, out, cv::Mat(H), img.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
  return out;
}

double nowMs()
{
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
std::vector<cv::Mat> loadGreyImages(const std::vector<std::string>& files)
{
  std::vector<cv::Mat> images;
  for (const auto& f : files)
  {
    cv::Mat img = cv::imread(f, cv::IMREAD_GRAYSCALE);
    if (img.empty())
      throw std::runtime_error("cannot read image " + f);
    if (!images.empty() && img.size() != images.front().size())
      throw std::runtime_error("image size differs from the first frame: " + f);
    images.push_back(img);
  }
  return images;
}

/** The transforms in the table's order, "none" first, with their homographies. */
using TTransforms = std::vector<std::pair<std::string, cv::Matx33d>>;

/** The two correspondence criteria every pair is scored with. */
struct TCriteria
{
  TCorrespondenceCriterion pixel, overlap;
};

/** Adds one (original, transformed) pair's figures to its row. */
void addPair(
    CFeatureBench::TRow& row, const TPairMetrics& m, const TPairMetrics& mo, std::size_t keypoints,
    double ms)
{
  row.frames++;
  row.keypointsPerFrame += static_cast<double>(keypoints);
  row.msPerFrame += ms;
  row.repeatability += m.repeatability;
  row.matchingScore += m.matchingScore;
  row.correspondencesPerFrame += static_cast<double>(m.correspondences);
  row.repeatabilityOverlap += mo.repeatability;
  row.matchingScoreOverlap += mo.matchingScore;
  row.correspondencesOverlapPerFrame += static_cast<double>(mo.correspondences);
  row.commonPerFrame += static_cast<double>(std::min(m.commonA, m.commonB));
}

/** The row's sums over its frames as means per frame. */
CFeatureBench::TRow averaged(CFeatureBench::TRow r)
{
  const double n = static_cast<double>(std::max<std::size_t>(1, r.frames));
  for (double* v :
       {&r.keypointsPerFrame, &r.msPerFrame, &r.repeatability, &r.matchingScore,
        &r.correspondencesPerFrame, &r.repeatabilityOverlap, &r.matchingScoreOverlap,
        &r.correspondencesOverlapPerFrame, &r.commonPerFrame})
    *v /= n;
  return r;
}

/** One extractor over every image and transform: a row of sums per
 *  transform (averaged() makes them means). The original image's features
 *  are described once and reused for every transform. */
std::vector<CFeatureBench::TRow> benchExtractor(
    const TExtractor& ex, const std::vector<cv::Mat>& images, const TTransforms& transforms,
    const TCriteria& crit, const CFeatureBench::TOptions& o)
{
  const int norm = ex.feature->defaultNorm();
  std::vector<CFeatureBench::TRow> rows(transforms.size());
  std::vector<std::vector<double>> finestErrors(transforms.size());
  for (std::size_t k = 0; k < transforms.size(); ++k)
  {
    rows[k].extractor = ex.name;
    rows[k].transform = transforms[k].first;
  }
  // One untimed warm-up: first-call allocations are not per-frame cost.
  {
    std::vector<cv::KeyPoint> k;
    cv::Mat d;
    ex.run(images.front(), k, d);
  }
  for (const auto& img : images)
  {
    std::vector<cv::KeyPoint> kpA;
    cv::Mat descA;
    double t0 = nowMs();
    ex.run(img, kpA, descA);
    const double msA = nowMs() - t0;
    for (std::size_t k = 0; k < transforms.size(); ++k)
    {
      const auto& [t, H] = transforms[k];
      std::vector<cv::KeyPoint> kpB;
      cv::Mat descB;  // a new buffer: the extractor would write into descA's
      double msB = msA;
      if (t == "none")
      {
        kpB = kpA;
        descB = descA;
      }
      else
      {
        const cv::Mat warped = applyTransform(img, t, H, o);
        t0 = nowMs();
        ex.run(warped, kpB, descB);
        msB = nowMs() - t0;
      }
      const TPairMetrics m =
          evaluatePair(kpA, descA, kpB, descB, H, img.size(), img.size(), norm, crit.pixel);
      // The finest scale's errors once, from the pixel criterion's matches.
      const TPairMetrics mo = evaluatePair(
          kpA, descA, kpB, descB, H, img.size(), img.size(), norm, crit.overlap, false);
      addPair(rows[k], m, mo, kpB.size(), msB);
      finestErrors[k].insert(
          finestErrors[k].end(), m.finestScaleErrors.begin(), m.finestScaleErrors.end());
    }
  }
  for (std::size_t k = 0; k < transforms.size(); ++k)
  {
    rows[k].localisationMatches = finestErrors[k].size() / 2;
    rows[k].localisationSigmaPx = localisationSigma(std::move(finestErrors[k]));
  }
  return rows;
}
}  // namespace

void CFeatureBench::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  input = c.read_string(s, "input", input);
  frames = c.read_int(s, "frames", frames);
  max_features = c.read_int(s, "max_features", max_features);
  extractors = splitList(c.read_string(s, "extractors", joinList(extractors)));
  transforms = splitList(c.read_string(s, "transforms", joinList(transforms)));
  blur_sigma = c.read_double(s, "blur_sigma", blur_sigma);
  brightness_offset = c.read_int(s, "brightness_offset", brightness_offset);
  pixel_tolerance = c.read_double(s, "pixel_tolerance", pixel_tolerance);
  border_margin = c.read_double(s, "border_margin", border_margin);
  max_overlap_error = c.read_double(s, "max_overlap_error", max_overlap_error);
  region_scale = c.read_double(s, "region_scale", region_scale);
  validate(s);
}

void CFeatureBench::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "input", input);
  c.write(s, "frames", frames);
  c.write(s, "max_features", max_features);
  c.write(s, "extractors", joinList(extractors));
  c.write(s, "transforms", joinList(transforms));
  c.write(s, "blur_sigma", blur_sigma);
  c.write(s, "brightness_offset", brightness_offset);
  c.write(s, "pixel_tolerance", pixel_tolerance);
  c.write(s, "border_margin", border_margin);
  c.write(s, "max_overlap_error", max_overlap_error);
  c.write(s, "region_scale", region_scale);
}

void CFeatureBench::TOptions::validate(const std::string& s) const
{
  const auto bad = [&](const std::string& key, const std::string& why)
  { throw std::invalid_argument("[" + s + "] " + key + ": " + why); };
  if (input.empty())
    bad("input", "required (a TUM folder with rgb.txt)");
  if (frames < 1)
    bad("frames", "must be >= 1");
  if (max_features < 0)
    bad("max_features", "must be >= 0 (0 = uncapped)");
  if (extractors.empty())
    bad("extractors", "empty list");
  for (const auto& e : extractors)
    if (std::find(kExtractors.begin(), kExtractors.end(), e) == kExtractors.end())
      bad("extractors", "unknown '" + e + "' (sift, surf, orb, akaze)");
  if (transforms.empty())
    bad("transforms", "empty list");
  for (const auto& t : transforms)
    if (std::find(kTransforms.begin(), kTransforms.end(), t) == kTransforms.end())
      bad("transforms", "unknown '" + t + "'");
  if (!(blur_sigma > 0))
    bad("blur_sigma", "must be > 0");
  if (!(pixel_tolerance > 0))
    bad("pixel_tolerance", "must be > 0");
  if (!(border_margin >= 0))
    bad("border_margin", "must be >= 0");
  if (!(max_overlap_error > 0 && max_overlap_error <= 1))
    bad("max_overlap_error", "must be in (0, 1]");
  if (!(region_scale > 0))
    bad("region_scale", "must be > 0");
}

std::vector<std::string> CFeatureBench::parseList(const std::string& commaList)
{
  return splitList(commaList);
}

const CFeatureBench::TRow* CFeatureBench::TResult::find(
    const std::string& extractor, const std::string& transform) const
{
  for (const auto& r : rows)
    if (r.extractor == extractor && r.transform == transform)
      return &r;
  return nullptr;
}

CFeatureBench::CFeatureBench(const TOptions& options) : m_options(options)
{
  m_options.validate();
}

cv::Matx33d CFeatureBench::homography(const std::string& t, const cv::Size& size)
{
  const cv::Point2f c(0.5f * (size.width - 1), 0.5f * (size.height - 1));
  cv::Mat A;
  if (t == "none" || t == "blur" || t == "brightness")
    return cv::Matx33d::eye();
  else if (t.rfind("rot", 0) == 0)
    A = cv::getRotationMatrix2D(c, std::stod(t.substr(3)), 1.0);
  else if (t.rfind("scale", 0) == 0)
    A = cv::getRotationMatrix2D(c, 0.0, std::stod(t.substr(5)));
  else
    throw std::invalid_argument("unknown transform '" + t + "'");
  cv::Matx33d H = cv::Matx33d::eye();
  for (int r = 0; r < 2; ++r)
    for (int k = 0; k < 3; ++k)
      H(r, k) = A.at<double>(r, k);
  return H;
}

std::vector<std::string> CFeatureBench::selectFrames(const std::string& dir, int n)
{
  const std::string list = dir + "/rgb.txt";
  std::ifstream in(list);
  if (!in)
    throw std::runtime_error("cannot open " + list);
  std::vector<std::string> files;
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo)
  {
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos)
      continue;
    std::istringstream ss(line);
    double stamp;
    std::string file;
    if (!(ss >> stamp >> file))
      throw std::runtime_error(
          "" + list + ":" + std::to_string(lineNo) + ": expected 'timestamp filename'");
    files.push_back(dir + "/" + file);
  }
  if (files.empty())
    throw std::runtime_error("no images listed in " + list);
  if (n >= static_cast<int>(files.size()))
    return files;
  std::vector<std::string> out;
  for (int k = 0; k < n; ++k)
  {
    const size_t idx =
        n == 1 ? 0
               : static_cast<size_t>(std::lround(
                     static_cast<double>(k) * static_cast<double>(files.size() - 1) / (n - 1)));
    out.push_back(files[idx]);
  }
  return out;
}

CFeatureBench::TResult CFeatureBench::run() const
{
  const TOptions& o = m_options;
  TResult res;
  res.input = o.input;
  res.maxFeatures = o.max_features;
  const std::vector<cv::Mat> images = loadGreyImages(selectFrames(o.input, o.frames));
  res.frames = images.size();
  res.imageSize = images.front().size();

  TTransforms transforms{{"none", homography("none", res.imageSize)}};
  for (const auto& t : o.transforms)
    if (t != "none")
      transforms.emplace_back(t, homography(t, res.imageSize));

  for (const auto& name : o.extractors)
  {
    const TExtractor ex = makeExtractor(name, o.max_features);
    TCriteria crit;
    crit.pixel.pixelTolerance = o.pixel_tolerance;
    crit.pixel.borderMargin = o.border_margin;
    crit.overlap = crit.pixel;
    crit.overlap.mode = TCorrespondenceCriterion::EMode::Overlap;
    crit.overlap.maxOverlapError = o.max_overlap_error;
    const std::optional<double> perSigma = sizePerBlobSigma(*ex.feature);
    crit.overlap.regionRadiusPerSize = perSigma ? o.region_scale / *perSigma : 0.5;
    res.regionRadiusPerSize[name] = crit.overlap.regionRadiusPerSize;
    res.regionCalibrated[name] = perSigma.has_value();
    for (auto& row : benchExtractor(ex, images, transforms, crit, o))
      res.rows.push_back(averaged(std::move(row)));
  }
  return res;
}

std::optional<double> CFeatureBench::sizePerBlobSigma(cv::Feature2D& extractor)
{
  constexpr double kSigma = 8.0;
  const cv::Point2d c(128.3, 127.6);  // non-integer on purpose
  double sum = 0;
  int n = 0;
  for (const double amp : {100.0, -100.0})
  {
    cv::Mat f(256, 256, CV_32F);
    for (int y = 0; y < f.rows; ++y)
      for (int x = 0; x < f.cols; ++x)
      {
        const double r2 = (x - c.x) * (x - c.x) + (y - c.y) * (y - c.y);
        f.at<float>(y, x) = static_cast<float>(128 + amp * std::exp(-r2 / (2 * kSigma * kSigma)));
      }
    cv::Mat img;
    f.convertTo(img, CV_8U);
    std::vector<cv::KeyPoint> kps;
    extractor.detect(img, kps);
    const cv::KeyPoint* best = nullptr;
    double bestD = 0.25 * kSigma;  // must sit on the blob
    for (const auto& k : kps)
    {
      const double d = cv::norm(cv::Point2d(k.pt) - c);
      if (d < bestD && k.size > 0)
      {
        bestD = d;
        best = &k;
      }
    }
    if (best)
    {
      sum += best->size / kSigma;
      ++n;
    }
  }
  if (n == 0)
    return std::nullopt;
  return sum / n;
}

std::string CFeatureBench::toTable(const TResult& r)
{
  std::ostringstream os;
  os << "feature-bench: " << r.input << ", " << r.frames << " frames " << r.imageSize.width << "x"
     << r.imageSize.height << ", cap "
     << (r.maxFeatures > 0 ? std::to_string(r.maxFeatures) : std::string("none")) << "\n";
  os << std::left << std::setw(8) << "extr" << std::setw(12) << "transform" << std::right
     << std::setw(9) << "kp/frame" << std::setw(10) << "ms/frame" << std::setw(9) << "repeat%"
     << std::setw(8) << "match%" << std::setw(11) << "corr/frame" << std::setw(10) << "ovRep%"
     << std::setw(9) << "ovMatch%" << std::setw(9) << "ovCorr" << std::setw(8) << "loc_px"
     << "\n";
  os << std::fixed;
  for (const auto& row : r.rows)
    os << std::left << std::setw(8) << row.extractor << std::setw(12) << row.transform << std::right
       << std::setprecision(0) << std::setw(9) << row.keypointsPerFrame << std::setprecision(1)
       << std::setw(10) << row.msPerFrame << std::setw(9) << 100 * row.repeatability << std::setw(8)
       << 100 * row.matchingScore << std::setprecision(0) << std::setw(11)
       << row.correspondencesPerFrame << std::setprecision(1) << std::setw(10)
       << 100 * row.repeatabilityOverlap << std::setw(9) << 100 * row.matchingScoreOverlap
       << std::setprecision(0) << std::setw(9) << row.correspondencesOverlapPerFrame
       << std::setprecision(3) << std::setw(8) << row.localisationSigmaPx << "\n";
  os << "repeat%/match%: pixel criterion ("
     << "H(a) within the pixel tolerance of b, sizes "
     << "within 1.29x); ov*: overlap error < max_overlap_error of circular regions; loc_px: "
     << "keypoint noise per axis at the finest detection scale, from the correct matches' "
     << "errors against H (1.4826 median|e| / sqrt 2)\n";
  for (const auto& [name, k] : r.regionRadiusPerSize)
  {
    const auto it = r.regionCalibrated.find(name);
    const bool cal = it != r.regionCalibrated.end() && it->second;
    os << "overlap region radius " << name << ": " << std::setprecision(3) << k << " x size ("
       << (cal ? "blob calibration" : "no blob detected: size / 2") << ")\n";
  }
  // Mean time over all images of each extractor, and SURF's speed-up on SIFT.
  std::map<std::string, std::pair<double, double>> time;  // sum, count
  for (const auto& row : r.rows)
  {
    time[row.extractor].first += row.msPerFrame;
    time[row.extractor].second += 1;
  }
  for (const auto& [name, tc] : time)
    os << "mean ms/frame " << name << ": " << std::setprecision(1) << tc.first / tc.second << "\n";
  if (time.count("sift") && time.count("surf"))
    os << "SURF speed-up over SIFT: " << std::setprecision(2)
       << (time["sift"].first / time["sift"].second) / (time["surf"].first / time["surf"].second)
       << "x\n";
  return os.str();
}

std::string CFeatureBench::toJson(const TResult& r)
{
  nlohmann::json j;
  j["input"] = r.input;
  j["max_features"] = r.maxFeatures;
  j["frames"] = r.frames;
  j["width"] = r.imageSize.width;
  j["height"] = r.imageSize.height;
  j["results"] = nlohmann::json::array();
  for (const auto& row : r.rows)
    j["results"].push_back(
        {{"extractor", row.extractor},
         {"transform", row.transform},
         {"frames", row.frames},
         {"keypoints_per_frame", row.keypointsPerFrame},
         {"ms_per_frame", row.msPerFrame},
         {"repeatability", row.repeatability},
         {"matching_score", row.matchingScore},
         {"correspondences_per_frame", row.correspondencesPerFrame},
         {"repeatability_overlap", row.repeatabilityOverlap},
         {"matching_score_overlap", row.matchingScoreOverlap},
         {"correspondences_overlap_per_frame", row.correspondencesOverlapPerFrame},
         {"common_per_frame", row.commonPerFrame},
         {"localisation_sigma_px", row.localisationSigmaPx},
         {"localisation_matches", row.localisationMatches}});
  return j.dump(2);
}
}  // namespace roislam::featurebench
