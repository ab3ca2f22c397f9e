/* roislam-stage-bench: Google Benchmark micro-benchmarks of the ROI pipeline
 * stages on 640x480 frames, for the speed figures of the project (frames per
 * second, ROI/traditional ratio, peak memory). Not a ctest test (only the tiny
 * benchmark_smoke check runs it).
 *
 * What is measured (every benchmark uses wall-clock time, counter "fps" is
 * calls per second):
 *  - PngDecode/{rgb,depth}: cv::imread of a colour PNG and a 16-bit depth PNG
 *    (synthetic frames: cv::imdecode of in-memory PNGs, as there are no files);
 *  - RoiDetect/{small,big}: CRoiDetector::detect on the grey image (stage 1);
 *  - Extract/<orb|sift|surf>/cap:<600|50|0>: CFeatureExtractor::extract on the
 *    grey image (stage 2; cap 0 = uncapped, ORB then uses OpenCV's 500);
 *  - Match/<type>/<flann|brute_force>: CFeatureMatcher::match between
 *    consecutive frames, 600 features each (stage 3);
 *  - HomographyLocate/<type>: CHomographyLocator::locate of the big-preset ROI
 *    of frame i in frame i+1 from precomputed ROI matches (stage 3);
 *  - FrontEnd/<traditional|roi_small|roi_big>/<orb|sift|surf>: a fresh
 *    CRgbdOdometry::process over the whole run of loaded frames per iteration
 *    (600 features, default front-end options); fps = frames per second,
 *    cpu_ms = process CPU time (all threads) per frame, *_ms = the front
 *    end's own per-stage wall times per frame.
 * After the benchmarks it prints a table "mode feature fps ms_per_frame
 * ratio_vs_traditional cpu_ms_per_frame cpu_ratio_vs_traditional" of the
 * FrontEnd runs; then, for the same modes and features, a paired comparison
 * (the three modes' odometries fed each frame in turn, so machine load hits
 * them alike: the ratio to trust on a shared machine); then the peak resident
 * memory (getrusage ru_maxrss). With --paired-slam-passes n, also the paired
 * end-to-end comparison of roi-graphslam's timed loop (bench::CPairedSlamCost,
 * the measurement roi-bench's speed table uses; CSlamPipeline: decoding
 * and the ROI one frame ahead, front end, back end, final optimisation; the
 * shipped config/<mode>.ini with 600 features): fps, cost ratio
 * mode / traditional (the ROI modes' <= 1.05 target) and ATE per mode. The
 * peak memory then covers all the pipelines held at once.
 *
 * Frames: the first --frames colour/depth pairs of the shared TUM sequence
 * (ROISLAM_SHARED_DATA_DIR/tum/rgbd_dataset_freiburg1_rpy_first250, or --data
 * <TUM folder or rawlog>); when that is absent, or with --synthetic, textured
 * synthetic frames generated in code (a camera sliding over a textured plane
 * 2 m away, with one densely written poster as the natural ROI).
 *
 * Run (Release build; whole program about 1 minute on 2 idle cores, 2 when they are
 * shared):
 *   cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
 *   cmake --build build --target roislam-stage-bench
 *   build/tests/benchmark/roislam-stage-bench --benchmark_min_time=0.2
 * Each benchmark runs until --benchmark_min_time seconds (SIFT and the
 * FrontEnd runs: at least one call / one run of all frames). On a shared
 * machine wall-clock figures vary by 10-30 % between runs; add
 * --benchmark_repetitions=3 (the table then averages the repetitions) and
 * compare the cpu_* columns, or pass --cv-threads 1 for single-thread costs.
 * Options of its own (in any order with the --benchmark_* flags):
 *   --data <dir>      TUM folder or .rawlog instead of the shared sequence
 *   --synthetic       use the synthetic frames even when real data exist
 *   --frames <n>      frames loaded / run through the front end (default 20)
 *   --cv-threads <n>  cv::setNumThreads (default: OpenCV's own choice)
 *   --paired-passes <n>  passes of the paired comparison (default 1, 0 = off)
 *   --config-dir <dir>  the <mode>.ini files of the end-to-end one (default
 *                     config/: e.g. a copy with [FrontEnd] roi_extraction = region)
 *   --paired-slam-passes <n>  passes of the end-to-end one (default 0 = off;
 *                     needs real frames: skipped with --synthetic)
 * Select stages with --benchmark_filter (e.g. 'FrontEnd', 'Extract/orb').
 */
#include <benchmark/benchmark.h>
#include <roislam/bench/CPairedSlamCost.h>
#include <roislam/bench/CostTiming.h>
#include <roislam/common/ProcessTuning.h>
#include <roislam/features/CFeatureExtractor.h>
#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/matching/CFeatureMatcher.h>
#include <roislam/matching/CHomographyLocator.h>
#include <roislam/roi/CRoiDetector.h>
#include <sys/resource.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef ROISLAM_SHARED_DATA_DIR
#define ROISLAM_SHARED_DATA_DIR ""
#endif

namespace
{
namespace fs = std::filesystem;
using roislam::bench::processCpuMs;
using roislam::bench::timed;
using roislam::features::CFeatureExtractor;
using roislam::features::EFeatureType;
using roislam::features::TFeatureSet;
using roislam::frontend::CRgbdOdometry;
using roislam::frontend::EFrontEndMode;
using roislam::io::TRGBDFrame;
using roislam::matching::CFeatureMatcher;
using roislam::matching::CHomographyLocator;
using roislam::matching::EMatcherType;
using roislam::roi::CRoiDetector;

const char* kSharedSequence = "tum/rgbd_dataset_freiburg1_rpy_first250";
constexpr int kMatchCap = 600;  // the experiments' feature cap

/** The frames every benchmark reads, loaded once before the benchmarks run. */
struct TBenchData
{
  std::string source;  // description for the context / table
  std::string path;    // TUM folder or rawlog the frames came from (empty: synthetic)
  bool synthetic = false;
  std::vector<TRGBDFrame> frames;
  std::vector<cv::Mat> grey;
  // PNG decode inputs: file paths (real data) or encoded buffers (synthetic).
  std::vector<std::string> rgbFiles, depthFiles;
  std::vector<std::vector<uchar>> rgbPng, depthPng;
};

TBenchData& data()
{
  static TBenchData d;
  return d;
}

// ---------------------------------------------------------------- frames ----

/** Non-comment "timestamp filename" entries of a TUM list file, as paths. */
std::vector<std::string> readTumList(const fs::path& listFile, std::size_t maxEntries)
{
  std::ifstream in(listFile);
  if (!in)
    throw std::runtime_error(listFile.string() + ": cannot open");
  std::vector<std::string> files;
  std::string line;
  for (int lineNo = 1; std::getline(in, line) && files.size() < maxEntries; ++lineNo)
  {
    if (line.empty() || line[0] == '#')
      continue;
    std::istringstream ss(line);
    double stamp = 0;
    std::string name;
    if (!(ss >> stamp >> name))
      throw std::runtime_error(
          listFile.string() + ":" + std::to_string(lineNo) + ": expected 'timestamp filename'");
    files.push_back((listFile.parent_path() / name).string());
  }
  return files;
}

void loadRealFrames(TBenchData& d, const std::string& path, std::size_t n)
{
  auto src = roislam::io::CFrameSource::open(path);
  while (d.frames.size() < n)
  {
    auto f = src->next();
    if (!f)
      break;
    if (f->rgb.cols != 640 || f->rgb.rows != 480)
      throw std::runtime_error(path + ": frames are not 640x480");
    d.frames.push_back(std::move(*f));
  }
  d.path = path;
  if (d.frames.size() < 2)
    throw std::runtime_error(path + ": fewer than 2 frames");
  d.source = path;
  if (fs::is_directory(path))
  {
    d.rgbFiles = readTumList(fs::path(path) / "rgb.txt", n);
    d.depthFiles = readTumList(fs::path(path) / "depth.txt", n);
  }
}

/** A textured plane seen by a camera sliding parallel to it: a wide canvas
 *  (soft gradient, scattered shapes of moderate contrast, one poster densely
 *  covered in black writing) cropped at a moving offset, plus sensor noise.
 *  Depth is the plane at 2 m, so consecutive frames are geometrically
 *  consistent for the RGB-D front end. */
void makeSyntheticFrames(TBenchData& d, std::size_t n)
{
  const int W = 640, H = 480, margin = 60;
  cv::RNG rng(12345);
  cv::Mat canvas(H + 2 * margin, W + 2 * margin, CV_8UC3);
  for (int r = 0; r < canvas.rows; ++r)
    for (int c = 0; c < canvas.cols; ++c)
      canvas.at<cv::Vec3b>(r, c) = cv::Vec3b(
          static_cast<uchar>(90 + c / 12), static_cast<uchar>(110 + r / 10),
          static_cast<uchar>(120 + (r + c) / 20));
  for (int i = 0; i < 120; ++i)
  {
    const cv::Point p(rng.uniform(0, canvas.cols), rng.uniform(0, canvas.rows));
    const cv::Scalar colour(rng.uniform(0, 255), rng.uniform(0, 255), rng.uniform(0, 255));
    if (i % 2)
      cv::circle(canvas, p, rng.uniform(4, 25), colour, cv::FILLED, cv::LINE_AA);
    else
      cv::rectangle(
          canvas, cv::Rect(p, cv::Size(rng.uniform(6, 50), rng.uniform(6, 50))), colour,
          cv::FILLED);
  }
  const cv::Rect poster(margin + 230, margin + 150, 230, 170);
  canvas(poster).setTo(cv::Scalar(245, 245, 245));
  const char* words[] = {"ROI", "landmark", "SLAM", "RGB-D", "TUM", "keyframe", "MRPT", "pose"};
  for (int y = poster.y + 16; y < poster.br().y - 4; y += 16)
  {
    std::string text;
    while (text.size() < 22)
      text += std::string(words[rng.uniform(0, 8)]) + " ";
    cv::putText(
        canvas, text, cv::Point(poster.x + 4, y), cv::FONT_HERSHEY_SIMPLEX, 0.42,
        cv::Scalar(10, 10, 10), 1, cv::LINE_AA);
  }

  const mrpt::img::TCamera camera = roislam::io::cameraPreset("ros");
  for (std::size_t k = 0; k < n; ++k)
  {
    const int dx = static_cast<int>(std::lround(40 * std::sin(0.15 * static_cast<double>(k))));
    const int dy = static_cast<int>(std::lround(25 * std::sin(0.10 * static_cast<double>(k))));
    TRGBDFrame f;
    f.index = k;
    f.timestamp = static_cast<double>(k) / 30.0;
    f.depthTimestamp = f.timestamp;
    cv::Mat noise(H, W, CV_16SC3);
    rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(2));
    cv::Mat crop;
    canvas(cv::Rect(margin + dx, margin + dy, W, H)).convertTo(crop, CV_16SC3);
    cv::Mat(crop + noise).convertTo(f.rgb, CV_8UC3);
    f.depth = cv::Mat(H, W, CV_32FC1, cv::Scalar(2.0f));
    f.camera = camera;
    d.frames.push_back(std::move(f));
  }
  d.synthetic = true;
  d.source = "synthetic (" + std::to_string(n) + " textured frames)";
}

void prepareData(const std::string& dataPath, bool synthetic, std::size_t n)
{
  TBenchData& d = data();
  const std::string shared = fs::path(ROISLAM_SHARED_DATA_DIR) / kSharedSequence;
  if (!dataPath.empty())
    loadRealFrames(d, dataPath, n);
  else if (!synthetic && !std::string(ROISLAM_SHARED_DATA_DIR).empty() && fs::exists(shared))
    loadRealFrames(d, shared, n);
  else
    makeSyntheticFrames(d, n);

  for (const auto& f : d.frames)
    d.grey.push_back(f.grey());
  if (d.rgbFiles.empty())
  {
    // No files to read: decode the frames' own PNG encodings from memory.
    for (const auto& f : d.frames)
    {
      std::vector<uchar> rgb, depth;
      cv::Mat depth16;
      f.depth.convertTo(depth16, CV_16UC1, 5000.0);  // TUM depth scale
      cv::imencode(".png", f.rgb, rgb);
      cv::imencode(".png", depth16, depth);
      d.rgbPng.push_back(std::move(rgb));
      d.depthPng.push_back(std::move(depth));
    }
  }
}

// ------------------------------------------------------------ benchmarks ----

/** Runs body and turns an exception into a benchmark error (the library
 *  itself does not catch). */
template <typename F>
void guarded(benchmark::State& state, F&& body)
{
  try
  {
    body();
  }
  catch (const std::exception& e)
  {
    state.SkipWithError(e.what());
  }
}

void setFps(benchmark::State& state, double calls)
{
  state.counters["fps"] = benchmark::Counter(calls, benchmark::Counter::kIsRate);
}

void bmPngDecode(benchmark::State& state, bool depth)
{
  guarded(
      state,
      [&]
      {
        const TBenchData& d = data();
        const bool files = !d.rgbFiles.empty();
        const std::size_t n = files ? (depth ? d.depthFiles.size() : d.rgbFiles.size())
                                    : (depth ? d.depthPng.size() : d.rgbPng.size());
        const int flags = depth ? cv::IMREAD_ANYDEPTH : cv::IMREAD_COLOR;
        std::size_t i = 0;
        for (auto _ : state)
        {
          const std::size_t k = i++ % n;
          cv::Mat img = files ? cv::imread(depth ? d.depthFiles[k] : d.rgbFiles[k], flags)
                              : cv::imdecode(depth ? d.depthPng[k] : d.rgbPng[k], flags);
          if (img.empty() || img.type() != (depth ? CV_16UC1 : CV_8UC3))
            throw std::runtime_error("PNG decode failed for frame " + std::to_string(k));
          benchmark::DoNotOptimize(img.data);
        }
        setFps(state, static_cast<double>(state.iterations()));
        state.SetLabel(files ? "imread" : "imdecode (synthetic, in memory)");
      });
}

void bmRoiDetect(benchmark::State& state, std::string preset)
{
  guarded(
      state,
      [&]
      {
        const TBenchData& d = data();
        CRoiDetector::TOptions o;
        o.setPreset(preset);
        const CRoiDetector detector(o);
        benchmark::DoNotOptimize(detector.detect(d.grey[0]));  // warm-up, untimed
        std::size_t i = 0, found = 0;
        double areaFraction = 0;
        for (auto _ : state)
        {
          const cv::Mat& g = d.grey[i++ % d.grey.size()];
          const auto roi = detector.detect(g);
          if (roi)
          {
            ++found;
            areaFraction += static_cast<double>(roi->box.area()) / static_cast<double>(g.total());
          }
        }
        setFps(state, static_cast<double>(state.iterations()));
        state.counters["roi_found"] =
            static_cast<double>(found) / static_cast<double>(state.iterations());
        state.counters["roi_area"] = found ? areaFraction / static_cast<double>(found) : 0.0;
      });
}

CFeatureExtractor makeExtractor(EFeatureType type, int cap)
{
  CFeatureExtractor::TOptions o;
  o.feature_type = type;
  o.max_features = cap;
  return CFeatureExtractor(o);
}

void bmExtract(benchmark::State& state, EFeatureType type, int cap)
{
  guarded(
      state,
      [&]
      {
        const TBenchData& d = data();
        const CFeatureExtractor extractor = makeExtractor(type, cap);
        // Untimed warm-up: the first calls pay for allocations (SIFT's big
        // pyramid buffers: measured ~3x slower on the first two calls) and the
        // OpenCV thread pool; SIFT often gets only one timed call.
        for (std::size_t k = 0; k < std::min<std::size_t>(3, d.grey.size()); ++k)
          benchmark::DoNotOptimize(extractor.extract(d.grey[k]).size());
        std::size_t i = 0, total = 0;
        for (auto _ : state)
          total += extractor.extract(d.grey[i++ % d.grey.size()]).size();
        setFps(state, static_cast<double>(state.iterations()));
        state.counters["features"] =
            static_cast<double>(total) / static_cast<double>(state.iterations());
      });
}

/** Features (cap 600) of every frame, computed once per type on first use. */
const std::vector<TFeatureSet>& cachedFeatures(EFeatureType type)
{
  static std::map<EFeatureType, std::vector<TFeatureSet>> cache;
  auto it = cache.find(type);
  if (it == cache.end())
  {
    const CFeatureExtractor extractor = makeExtractor(type, kMatchCap);
    std::vector<TFeatureSet> sets;
    for (const auto& g : data().grey)
      sets.push_back(extractor.extract(g));
    it = cache.emplace(type, std::move(sets)).first;
  }
  return it->second;
}

void bmMatch(benchmark::State& state, EFeatureType type, EMatcherType matcherType)
{
  guarded(
      state,
      [&]
      {
        // Set-up before the loop is not timed.
        const auto& sets = cachedFeatures(type);
        CFeatureMatcher::TOptions o;
        o.matcher = matcherType;
        const CFeatureMatcher matcher(o);
        benchmark::DoNotOptimize(matcher.match(sets[0], sets[1]).size());  // warm-up
        const std::size_t pairs = sets.size() - 1;
        std::size_t i = 0, total = 0;
        for (auto _ : state)
        {
          const std::size_t k = i++ % pairs;
          total += matcher.match(sets[k], sets[k + 1]).size();
        }
        setFps(state, static_cast<double>(state.iterations()));
        state.counters["matches"] =
            static_cast<double>(total) / static_cast<double>(state.iterations());
      });
}

/** One ROI-relocation problem: ROI features of frame i matched into frame i+1. */
struct TLocateCase
{
  TFeatureSet roiFeatures;
  cv::Rect roi;
  const TFeatureSet* other = nullptr;
  cv::Size otherSize;
  std::vector<cv::DMatch> matches;
};

void bmHomographyLocate(benchmark::State& state, EFeatureType type)
{
  guarded(
      state,
      [&]
      {
        const TBenchData& d = data();
        const auto& sets = cachedFeatures(type);
        CRoiDetector::TOptions ro;
        ro.setPreset("big");
        const CRoiDetector detector(ro);
        const CFeatureMatcher matcher;
        std::vector<TLocateCase> cases;
        for (std::size_t k = 0; k + 1 < sets.size(); ++k)
        {
          const auto roi = detector.detect(d.grey[k]);
          if (!roi)
            continue;
          TLocateCase c;
          c.roi = roi->box;
          c.roiFeatures = sets[k].subset(roi->box);
          c.other = &sets[k + 1];
          c.otherSize = d.grey[k + 1].size();
          c.matches = matcher.match(c.roiFeatures, *c.other);
          cases.push_back(std::move(c));
        }
        if (cases.empty())
          throw std::runtime_error("no ROI detected in any frame");
        const CHomographyLocator locator;
        std::size_t i = 0, located = 0, inliers = 0;
        for (auto _ : state)
        {
          const TLocateCase& c = cases[i++ % cases.size()];
          const auto r = locator.locate(c.roiFeatures, c.roi, *c.other, c.otherSize, c.matches);
          if (r)
          {
            ++located;
            inliers += r->inliers.size();
          }
        }
        setFps(state, static_cast<double>(state.iterations()));
        state.counters["located"] =
            static_cast<double>(located) / static_cast<double>(state.iterations());
        state.counters["inliers"] =
            located ? static_cast<double>(inliers) / static_cast<double>(located) : 0.0;
      });
}

void bmFrontEnd(benchmark::State& state, EFrontEndMode mode, EFeatureType type)
{
  guarded(
      state,
      [&]
      {
        const TBenchData& d = data();
        CRgbdOdometry::TOptions o;
        o.mode = mode;
        o.extractor.feature_type = type;
        o.extractor.max_features = kMatchCap;
        std::size_t frames = 0, roiTracked = 0, fallback = 0, icp = 0, lost = 0;
        double roiMs = 0, extractMs = 0, matchMs = 0, ransacMs = 0, cpuMs = 0;
        for (auto _ : state)
        {
          state.PauseTiming();
          CRgbdOdometry odo(o);
          odo.setMinLoggingLevel(mrpt::system::LVL_ERROR);
          state.ResumeTiming();
          const double cpu0 = processCpuMs();
          for (const auto& f : d.frames)
          {
            const auto r = odo.process(f);
            roiMs += r.times.roi_ms;
            extractMs += r.times.extract_ms;
            matchMs += r.times.match_ms;
            ransacMs += r.times.ransac_ms;
          }
          cpuMs += processCpuMs() - cpu0;
          const auto& s = odo.stats();
          frames += s.frames;
          roiTracked += s.roiFeatures;
          fallback += s.fullImageFallback;
          icp += s.depthIcp;
          lost += s.lost;
        }
        const double nf = static_cast<double>(std::max<std::size_t>(frames, 1));
        setFps(state, static_cast<double>(frames));
        state.counters["cpu_ms"] = cpuMs / nf;
        state.counters["roi_ms"] = roiMs / nf;
        state.counters["extract_ms"] = extractMs / nf;
        state.counters["match_ms"] = matchMs / nf;
        state.counters["ransac_ms"] = ransacMs / nf;
        state.counters["roi_tracked"] = static_cast<double>(roiTracked) / nf;
        state.counters["fallback"] = static_cast<double>(fallback) / nf;
        state.counters["icp"] = static_cast<double>(icp) / nf;
        state.counters["lost"] = static_cast<double>(lost) / nf;
      });
}

// --------------------------------------------------------------- report ----

/** Console output as usual, plus a record of the FrontEnd fps figures and of
 *  any benchmark that failed, for the summary table after the run. */
class CCollectingReporter : public benchmark::ConsoleReporter
{
 public:
  using ConsoleReporter::ConsoleReporter;

  void ReportRuns(const std::vector<Run>& runs) override
  {
    ConsoleReporter::ReportRuns(runs);
    for (const auto& r : runs)
    {
      if (r.error_occurred)
      {
        failed.push_back(r.benchmark_name() + ": " + r.error_message);
        continue;
      }
      const std::string name = r.run_name.function_name;
      const auto fps = r.counters.find("fps");
      const auto cpu = r.counters.find("cpu_ms");
      if (name.rfind("FrontEnd/", 0) != 0 || fps == r.counters.end() || cpu == r.counters.end())
        continue;
      // Single runs, or the "mean" aggregate when only aggregates are reported
      // (--benchmark_report_aggregates_only); never both for one benchmark.
      const bool mean = r.run_type == Run::RT_Aggregate && r.aggregate_name == "mean";
      if (r.run_type != Run::RT_Iteration && !mean)
        continue;
      auto& figures = mean ? m_means : frontEnd;
      TFigures& acc = figures[name.substr(std::string("FrontEnd/").size())];
      acc.fps += fps->second.value;
      acc.cpuMs += cpu->second.value;
      acc.runs += 1;
    }
  }

  /** Sums over repetitions of one FrontEnd benchmark. */
  struct TFigures
  {
    double fps = 0;    //!< wall-clock frames per second
    double cpuMs = 0;  //!< process CPU ms per frame
    int runs = 0;
  };
  /** "mode/feature" -> figures. */
  std::map<std::string, TFigures> frontEnd;
  std::vector<std::string> failed;

  /** Adds the "mean" aggregates of benchmarks that reported no single run. */
  void useMeansWhereMissing()
  {
    for (const auto& [key, figures] : m_means)
      frontEnd.emplace(key, figures);
  }

 private:
  std::map<std::string, TFigures> m_means;
};

void printFrontEndTable(const CCollectingReporter& rep)
{
  if (rep.frontEnd.empty())
    return;
  std::cout << "\nFront-end per-frame cost (CRgbdOdometry::process, " << data().frames.size()
            << " frames of " << data().source << ")\n"
            << std::left << std::setw(12) << "mode" << std::setw(8) << "feature" << std::right
            << std::setw(9) << "fps" << std::setw(14) << "ms_per_frame" << std::setw(22)
            << "ratio_vs_traditional" << std::setw(18) << "cpu_ms_per_frame" << std::setw(26)
            << "cpu_ratio_vs_traditional"
            << "\n";
  for (const char* feature : {"orb", "sift", "surf"})
  {
    const auto trad = rep.frontEnd.find(std::string("traditional/") + feature);
    for (const char* mode : {"traditional", "roi_small", "roi_big"})
    {
      const auto it = rep.frontEnd.find(std::string(mode) + "/" + feature);
      if (it == rep.frontEnd.end())
        continue;
      const double fps = it->second.fps / it->second.runs;
      const double cpuMs = it->second.cpuMs / it->second.runs;
      std::cout << std::left << std::setw(12) << mode << std::setw(8) << feature << std::right
                << std::fixed << std::setprecision(2) << std::setw(9) << fps << std::setw(14)
                << 1000.0 / fps;
      if (trad != rep.frontEnd.end())
        std::cout << std::setw(22) << fps / (trad->second.fps / trad->second.runs);
      else
        std::cout << std::setw(22) << "n/a";
      std::cout << std::setw(18) << cpuMs;
      if (trad != rep.frontEnd.end())
        std::cout << std::setw(26) << (trad->second.cpuMs / trad->second.runs) / cpuMs;
      else
        std::cout << std::setw(26) << "n/a";
      std::cout << "\n";
    }
  }
  std::cout << "ratio_vs_traditional = fps(mode) / fps(traditional), same feature (wall clock);\n"
               "cpu_ratio_vs_traditional = cpu_ms(traditional) / cpu_ms(mode) (process CPU, all\n"
               "threads: less sensitive to other load on the machine). > 1 means the ROI mode is "
               "faster.\n";
}

/** The modes of the paired comparisons, traditional first. */
const EFrontEndMode kPairedModes[] = {
    EFrontEndMode::Traditional, EFrontEndMode::RoiSmall, EFrontEndMode::RoiBig};

/** Indices into kPairedModes of the modes whose FrontEnd benchmark ran for
 *  `type` (so the paired tables honour --benchmark_filter). */
std::vector<std::size_t> modesRun(const CCollectingReporter& rep, EFeatureType type)
{
  std::vector<std::size_t> used;
  for (std::size_t m = 0; m < 3; ++m)
    if (rep.frontEnd.count(roislam::frontend::toString(kPairedModes[m]) + "/" + toString(type)))
      used.push_back(m);
  return used;
}

/** Paired comparison that contention on a shared machine cannot bias: for each
 *  feature type benchmarked, one odometry per mode, fed the same frame in turn
 *  (mode order rotated per frame), timing each process() call. Prints per-frame
 *  wall and process-CPU cost and their ratios to traditional. */
void printPairedTable(const CCollectingReporter& rep, int passes)
{
  if (rep.frontEnd.empty() || passes <= 0)
    return;
  const TBenchData& d = data();
  const auto& modes = kPairedModes;
  std::cout << "\nPaired front-end cost (modes interleaved frame by frame, " << passes << " x "
            << d.frames.size() << " frames)\n"
            << std::left << std::setw(12) << "mode" << std::setw(8) << "feature" << std::right
            << std::setw(14) << "ms_per_frame" << std::setw(22) << "ratio_vs_traditional"
            << std::setw(18) << "cpu_ms_per_frame" << std::setw(26) << "cpu_ratio_vs_traditional"
            << "\n";
  for (const auto type : {EFeatureType::ORB, EFeatureType::SIFT, EFeatureType::SURF})
  {
    const std::vector<std::size_t> used = modesRun(rep, type);
    if (used.empty())
      continue;
    double wallMs[3] = {0, 0, 0}, cpuMs[3] = {0, 0, 0};
    std::size_t calls = 0;
    for (int pass = 0; pass < passes; ++pass)
    {
      std::vector<std::unique_ptr<CRgbdOdometry>> odo(3);
      for (const std::size_t m : used)
      {
        CRgbdOdometry::TOptions o;
        o.mode = modes[m];
        o.extractor.feature_type = type;
        o.extractor.max_features = kMatchCap;
        odo[m] = std::make_unique<CRgbdOdometry>(o);
        odo[m]->setMinLoggingLevel(mrpt::system::LVL_ERROR);
      }
      for (std::size_t k = 0; k < d.frames.size(); ++k, ++calls)
        for (std::size_t j = 0; j < used.size(); ++j)
        {
          const std::size_t m = used[(j + k) % used.size()];
          timed(
              [&] { benchmark::DoNotOptimize(odo[m]->process(d.frames[k]).inliers); }, wallMs[m],
              cpuMs[m]);
        }
    }
    const bool haveTrad = used.front() == 0;
    for (const std::size_t m : used)
    {
      const double n = static_cast<double>(calls);
      std::cout << std::left << std::setw(12) << roislam::frontend::toString(modes[m])
                << std::setw(8) << toString(type) << std::right << std::fixed
                << std::setprecision(2) << std::setw(14) << wallMs[m] / n;
      if (haveTrad)
        std::cout << std::setw(22) << wallMs[0] / wallMs[m];
      else
        std::cout << std::setw(22) << "n/a";
      std::cout << std::setw(18) << cpuMs[m] / n;
      if (haveTrad)
        std::cout << std::setw(26) << cpuMs[0] / cpuMs[m];
      else
        std::cout << std::setw(26) << "n/a";
      std::cout << "\n";
    }
  }
  std::cout << "ratio = cost(traditional) / cost(mode): > 1 means the ROI mode is faster.\n";
}

/** Paired end-to-end comparison, what roi-graphslam's fps measures:
 *  bench::CPairedSlamCost on the modes benchmarked, each configured by the
 *  shipped config/<mode>.ini (600 features of the benchmarked type), stepped
 *  in turn frame by frame (order rotated). Prints wall and process-CPU cost
 *  per frame, the front end's own time and the cost ratios mode / traditional. */
void printPairedSlamTable(const CCollectingReporter& rep, int passes, const std::string& configDir)
{
  if (rep.frontEnd.empty() || passes <= 0)
    return;
  const TBenchData& d = data();
  if (d.path.empty())
  {
    std::cout << "\nPaired end-to-end SLAM cost: skipped (needs a TUM folder or rawlog, not "
                 "synthetic frames)\n";
    return;
  }
  const auto& modes = kPairedModes;
  std::cout << "\nPaired end-to-end SLAM cost (decode + ROI ahead + front end + back end, "
               "config/<mode>.ini, modes interleaved frame by frame, "
            << passes << " x " << d.frames.size() << " frames)\n"
            << std::left << std::setw(12) << "mode" << std::setw(8) << "feature" << std::right
            << std::setw(8) << "fps" << std::setw(14) << "ms_per_frame" << std::setw(16)
            << "cost_vs_trad" << std::setw(18) << "cpu_ms_per_frame" << std::setw(20)
            << "cpu_cost_vs_trad" << std::setw(14) << "frontend_ms" << std::setw(16)
            << "fe_cost_vs_trad" << std::setw(8) << "ATE_m"
            << "\n";
  for (const auto type : {EFeatureType::ORB, EFeatureType::SIFT, EFeatureType::SURF})
  {
    const std::vector<std::size_t> used = modesRun(rep, type);
    if (used.empty())
      continue;
    roislam::bench::CPairedSlamCost::TOptions o;
    o.sequence = d.path;
    o.feature = type;
    o.max_features = kMatchCap;
    o.passes = passes;
    o.max_frames = d.frames.size();
    for (const std::size_t m : used)
    {
      const std::string mode = roislam::frontend::toString(modes[m]);
      o.versions.push_back({mode, "", configDir + "/" + mode + ".ini", {}});
    }
    const auto cost = roislam::bench::CPairedSlamCost(o).run();
    // The ratios are to the first mode run: shown only when it is traditional.
    const bool haveTrad = used.front() == 0;
    const auto ratio = [&](double r) -> std::string
    {
      if (!haveTrad)
        return "n/a";
      std::ostringstream ss;
      ss << std::fixed << std::setprecision(2) << r;
      return ss.str();
    };
    for (const auto& v : cost.versions)
    {
      std::cout << std::left << std::setw(12) << v.key << std::setw(8) << toString(type)
                << std::right << std::fixed << std::setprecision(1) << std::setw(8) << v.fps
                << std::setprecision(2) << std::setw(14) << v.wallMsPerFrame << std::setw(16)
                << ratio(v.wallRatio) << std::setw(18) << v.cpuMsPerFrame << std::setw(20)
                << ratio(v.cpuRatio) << std::setw(14) << v.frontEndMsPerFrame << std::setw(16)
                << ratio(v.frontEndRatio);
      if (v.ateRmse)
        std::cout << std::setprecision(4) << std::setw(8) << *v.ateRmse;
      else
        std::cout << std::setw(8) << "n/a";
      std::cout << "\n";
    }
  }
  std::cout << "cost_vs_trad = cost(mode) / cost(traditional), end to end; fe_cost_vs_trad the "
               "same for the front end's own time (decode excluded): the ROI modes' targets "
               "(issue 15) are SIFT <= 0.5, SURF and ORB <= 0.7.\n";
}

void registerBenchmarks()
{
  using benchmark::RegisterBenchmark;
  std::vector<benchmark::internal::Benchmark*> all;
  all.push_back(RegisterBenchmark("PngDecode/rgb", bmPngDecode, false));
  all.push_back(RegisterBenchmark("PngDecode/depth", bmPngDecode, true));
  for (const char* preset : {"small", "big"})
    all.push_back(RegisterBenchmark(
        (std::string("RoiDetect/") + preset).c_str(), bmRoiDetect, std::string(preset)));
  const EFeatureType types[] = {EFeatureType::ORB, EFeatureType::SIFT, EFeatureType::SURF};
  for (const auto t : types)
    for (const int cap : {600, 50, 0})
      all.push_back(RegisterBenchmark(
          ("Extract/" + toString(t) + "/cap:" + std::to_string(cap)).c_str(), bmExtract, t, cap));
  for (const auto t : types)
  {
    all.push_back(RegisterBenchmark(
        ("Match/" + toString(t) + "/flann").c_str(), bmMatch, t, EMatcherType::FLANN));
    all.push_back(RegisterBenchmark(
        ("Match/" + toString(t) + "/brute_force").c_str(), bmMatch, t, EMatcherType::BRUTE_FORCE));
  }
  for (const auto t : types)
    all.push_back(
        RegisterBenchmark(("HomographyLocate/" + toString(t)).c_str(), bmHomographyLocate, t));
  for (const auto t : types)
    for (const auto m :
         {EFrontEndMode::Traditional, EFrontEndMode::RoiSmall, EFrontEndMode::RoiBig})
      all.push_back(RegisterBenchmark(
          ("FrontEnd/" + roislam::frontend::toString(m) + "/" + toString(t)).c_str(), bmFrontEnd, m,
          t));
  for (auto* b : all)
    b->UseRealTime()->Unit(benchmark::kMillisecond);
}
/** --help (handled by benchmark::Initialize): its flags plus ours. */
void printUsage()
{
  benchmark::PrintDefaultHelp();
  std::cout << "roislam-stage-bench options:\n"
               "  [--data <TUM folder or .rawlog>]  (default: the shared TUM sequence)\n"
               "  [--synthetic]                     synthetic frames even if real data exist\n"
               "  [--frames <n>]                    frames loaded / run (default 20)\n"
               "  [--cv-threads <n>]                cv::setNumThreads (default OpenCV's)\n"
               "  [--paired-passes <n>]             paired front-end comparison (default 1)\n"
               "  [--paired-slam-passes <n>]        paired end-to-end SLAM comparison (default 0)\n"
               "  [--config-dir <dir>]              its <mode>.ini files (default: config/)\n";
}
}  // namespace

int main(int argc, char** argv)
{
  // As the apps do, so that stage times match theirs.
  roislam::common::tuneAllocatorForImages();
  try
  {
    benchmark::Initialize(&argc, argv, &printUsage);
    CLI::App app{"roislam-stage-bench: per-stage micro-benchmarks (plus --benchmark_* flags)"};
    std::string dataPath;
    bool synthetic = false;
    std::size_t frames = 20;
    int cvThreads = -1;
    int pairedPasses = 1;
    int pairedSlamPasses = 0;
    std::string configDir = ROISLAM_CONFIG_DIR;
    app.add_option("--data", dataPath, "TUM folder or .rawlog (default: the shared TUM sequence)");
    app.add_flag("--synthetic", synthetic, "use synthetic frames even when real data exist");
    app.add_option("--frames", frames, "frames loaded and run through the front end")
        ->check(CLI::Range(std::size_t{2}, std::size_t{10000}));
    app.add_option("--cv-threads", cvThreads, "cv::setNumThreads (default: OpenCV's choice)");
    app.add_option(
           "--paired-passes", pairedPasses,
           "passes of the interleaved front-end comparison after the benchmarks (0 = off)")
        ->check(CLI::Range(0, 100));
    app.add_option(
           "--paired-slam-passes", pairedSlamPasses,
           "passes of the interleaved end-to-end SLAM comparison (0 = off)")
        ->check(CLI::Range(0, 100));
    app.add_option(
        "--config-dir", configDir,
        "folder of the traditional/roi_small/roi_big .ini files of the end-to-end comparison");
    try
    {
      app.parse(argc, argv);
    }
    catch (const CLI::ParseError& e)
    {
      return app.exit(e);
    }
    if (cvThreads >= 0)
      cv::setNumThreads(cvThreads);

    prepareData(dataPath, synthetic, frames);
    benchmark::AddCustomContext("frames", data().source);
    benchmark::AddCustomContext("frame_count", std::to_string(data().frames.size()));
    benchmark::AddCustomContext("opencv_threads", std::to_string(cv::getNumThreads()));
    registerBenchmarks();

    CCollectingReporter reporter(
        isatty(STDOUT_FILENO) ? benchmark::ConsoleReporter::OO_ColorTabular
                              : benchmark::ConsoleReporter::OO_Tabular);
    const std::size_t ran = benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    reporter.useMeansWhereMissing();

    printFrontEndTable(reporter);
    printPairedTable(reporter, pairedPasses);
    printPairedSlamTable(reporter, pairedSlamPasses, configDir);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::cout << "\npeak memory (ru_maxrss): " << std::fixed << std::setprecision(1)
              << static_cast<double>(usage.ru_maxrss) / 1024.0 << " MiB\n";

    if (ran == 0)
      throw std::runtime_error("no benchmark matched --benchmark_filter");
    if (!reporter.failed.empty())
    {
      for (const auto& f : reporter.failed)
        std::cerr << "roislam-stage-bench: failed: " << f << "\n";
      return 1;
    }
    return 0;
  }
  catch (const std::exception& e)
  {
    std::cerr << "roislam-stage-bench: error: " << e.what() << "\n";
    return 1;
  }
}
