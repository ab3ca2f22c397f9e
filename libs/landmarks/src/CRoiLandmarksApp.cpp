#include "roislam/landmarks/CRoiLandmarksApp.h"

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <mutex>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <thread>

#include "roislam/common/COutputFolder.h"
#include "roislam/io/CFrameSource.h"
#include "roislam/io/TumTrajectory.h"
#include "roislam/landmarks/CLandmarkScorer.h"
#include "roislam/landmarks/CObservationProcessor.h"

namespace fs = std::filesystem;

namespace roislam::landmarks
{
namespace
{
/** Reads frames on a second thread (PNG decoding costs about as much as the
 *  ORB pipeline), a few frames ahead of the consumer. */
class CFramePrefetcher
{
 public:
  CFramePrefetcher(io::CFrameSource& source, std::size_t maxFrames)
      : m_thread([this, &source, maxFrames] { run(source, maxFrames); })
  {
  }
  ~CFramePrefetcher()
  {
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_stop = true;
    }
    m_cv.notify_all();
    m_thread.join();
  }

  /** The next frame, nullopt at the end; rethrows the reader's exception. */
  std::optional<io::TRGBDFrame> next()
  {
    std::unique_lock<std::mutex> lock(m_mutex);
    m_cv.wait(lock, [&] { return !m_queue.empty() || m_done; });
    if (m_queue.empty())
    {
      if (m_error)
        std::rethrow_exception(m_error);
      return std::nullopt;
    }
    io::TRGBDFrame f = std::move(m_queue.front());
    m_queue.pop_front();
    m_cv.notify_all();
    return f;
  }

 private:
  void run(io::CFrameSource& source, std::size_t maxFrames)
  {
    try
    {
      for (std::size_t n = 0; maxFrames == 0 || n < maxFrames; ++n)
      {
        auto f = source.next();
        std::unique_lock<std::mutex> lock(m_mutex);
        if (!f || m_stop)
          break;
        m_queue.push_back(std::move(*f));
        m_cv.notify_all();
        m_cv.wait(lock, [&] { return m_queue.size() < kDepth || m_stop; });
        if (m_stop)
          break;
      }
    }
    catch (...)
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(m_mutex);
    m_done = true;
    m_cv.notify_all();
  }

  static constexpr std::size_t kDepth = 4;
  std::mutex m_mutex;
  std::condition_variable m_cv;
  std::deque<io::TRGBDFrame> m_queue;
  bool m_done = false;
  bool m_stop = false;
  std::exception_ptr m_error;
  std::thread m_thread;  // last: starts after the other members exist
};

void writeTextAtomically(const std::string& file, const std::string& text)
{
  const std::string tmp = file + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!f)
      throw std::runtime_error(file + ": cannot write");
    f << text;
    f.close();
    if (!f)
      throw std::runtime_error(file + ": cannot write");
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec)
    throw std::runtime_error(file + ": cannot write: " + ec.message());
}

std::string frameName(uint64_t frame)
{
  std::ostringstream os;
  os << std::setw(6) << std::setfill('0') << frame;
  return os.str();
}

/** An RGB-D observation for the annotated rawlog: raw TUM-scaled depth in an
 *  external .bin, the colour image external (the source PNG when it exists,
 *  else a PNG written next to the depth). */
mrpt::obs::CObservation3DRangeScan makeScan(
    const io::TRGBDFrame& f, const std::string& imagesDir, const mrpt::poses::CPose3D& sensorPose)
{
  mrpt::obs::CObservation3DRangeScan obs;
  obs.sensorLabel = "RGBD";
  obs.timestamp = mrpt::Clock::fromDouble(f.timestamp);
  obs.sensorPose = sensorPose;
  obs.cameraParams = f.camera;
  obs.cameraParams.ncols = static_cast<uint32_t>(f.depth.cols);
  obs.cameraParams.nrows = static_cast<uint32_t>(f.depth.rows);
  obs.cameraParamsIntensity = obs.cameraParams;
  obs.range_is_depth = true;
  obs.maxRange = 10;
  obs.hasRangeImage = true;
  obs.rangeUnits = 1.0f / 5000;
  obs.rangeImage_setSize(f.depth.rows, f.depth.cols);
  for (int r = 0; r < f.depth.rows; ++r)
  {
    const float* row = f.depth.ptr<float>(r);
    for (int c = 0; c < f.depth.cols; ++c)
    {
      const double v = std::isfinite(row[c]) && row[c] > 0 ? std::lround(row[c] * 5000.0) : 0;
      obs.rangeImage(r, c) = static_cast<uint16_t>(std::min(v, 65535.0));
    }
  }
  const std::string name = frameName(f.index);
  obs.hasIntensityImage = true;
  std::error_code ec;
  if (!f.rgbSource.empty() && fs::is_regular_file(f.rgbSource, ec))
    obs.intensityImage.setExternalStorage(fs::absolute(f.rgbSource).string());
  else
  {
    const std::string png = imagesDir + "/" + name + "_rgb.png";
    if (!cv::imwrite(png, f.rgb))
      throw std::runtime_error(png + ": cannot write");
    obs.intensityImage.setExternalStorage(name + "_rgb.png");
  }
  obs.rangeImage_convertToExternalStorage(name + "_depth.bin", imagesDir + "/");
  return obs;
}

/** `file` relative to `dir` when it lies inside it. */
std::optional<fs::path> pathInside(const std::string& file, const std::string& dir)
{
  const fs::path rel = fs::absolute(file).lexically_normal().lexically_relative(
      fs::absolute(dir).lexically_normal());
  if (rel.empty() || *rel.begin() == "..")
    return std::nullopt;
  return rel;
}

std::string fmt(double v, int precision = 4)
{
  if (!std::isfinite(v))
    return "nan";
  std::ostringstream os;
  os << std::fixed << std::setprecision(precision) << v;
  return os.str();
}

template <typename T>
nlohmann::json orNull(const std::optional<T>& v)
{
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}
}  // namespace

const std::vector<std::string>& CRoiLandmarksApp::outputFiles()
{
  static const std::vector<std::string> names{
      "frames.csv", "landmarks", "landmarks.db", "summary.json"};
  return names;
}

common::COutputFolder::TOptions CRoiLandmarksApp::outputFolderOptions(
    const std::optional<fs::path>& rawlogInFolder) const
{
  common::COutputFolder::TOptions o;
  o.overwrite = m_args.overwrite;
  o.known = outputFiles();
  if (rawlogInFolder)
  {
    // The annotated rawlog and its images folder, wherever they are inside.
    const fs::path& r = *rawlogInFolder;
    o.known.push_back(r.begin()->string());
    const fs::path images = r.parent_path() / (r.stem().string() + "_Images");
    o.known.push_back(images.begin()->string());
  }
  return o;
}

CRoiLandmarksApp::CRoiLandmarksApp(TArguments arguments) : m_args(std::move(arguments))
{
  if (!m_args.iniFile.empty())
    m_options.loadFromFile(m_args.iniFile);
  if (m_args.feature)
    m_options.features.feature_type = features::featureTypeFromString(*m_args.feature);
  if (m_args.maxFeatures)
  {
    if (*m_args.maxFeatures < 0)
      throw std::invalid_argument(
          "--max-features must be >= 0 (got " + std::to_string(*m_args.maxFeatures) + ")");
    m_options.features.max_features = *m_args.maxFeatures;
  }
  if (m_args.roiPreset)
    m_options.roi.setPreset(*m_args.roiPreset);
  if (m_args.input.empty())
    throw std::invalid_argument("no input given");
  if (m_args.outputDir.empty())
    throw std::invalid_argument("no output folder given");
}

CRoiLandmarksApp::TSummary CRoiLandmarksApp::run()
{
  const auto wall0 = std::chrono::steady_clock::now();
  auto progress = [&](const std::string& s)
  {
    if (m_args.progress)
      m_args.progress(s);
  };

  // Complete or absent: everything goes to a staging folder renamed at the end.
  const auto rawlogInFolder = m_args.outputRawlog
                                  ? pathInside(*m_args.outputRawlog, m_args.outputDir)
                                  : std::optional<fs::path>();
  common::COutputFolder folder(m_args.outputDir, outputFolderOptions(rawlogInFolder));
  const fs::path outDir(folder.path());
  std::error_code ec;
  const fs::path patchesDir = outDir / "landmarks";
  fs::create_directories(patchesDir, ec);
  if (ec)
    throw std::runtime_error(patchesDir.string() + ": cannot create folder");

  auto source = io::CFrameSource::open(m_args.input, m_args.camera);
  std::optional<CLandmarkScorer> scorer;
  const auto gtFile = source->groundTruthFile();
  if (gtFile && fs::is_regular_file(*gtFile))
    scorer.emplace(m_options.scoring, io::loadTumTrajectory(*gtFile));
  progress(
      "roi-landmarks: " + source->name() + ", " + std::to_string(source->size()) + " frames, " +
      features::toString(m_options.features.feature_type) + ", ROI preset " + m_options.roi.preset +
      (scorer ? ", ground truth " + *gtFile : ", no ground truth"));

  // Annotated rawlog: written to a temporary name, renamed at the end.
  std::unique_ptr<mrpt::io::CFileGZOutputStream> rawlog;
  std::string rawlogTmp, imagesDir;
  if (m_args.outputRawlog)
  {
    const fs::path rl = rawlogInFolder ? outDir / *rawlogInFolder : fs::path(*m_args.outputRawlog);
    imagesDir = (rl.parent_path() / (rl.stem().string() + "_Images")).string();
    if (rl.has_parent_path())
      fs::create_directories(rl.parent_path(), ec);
    fs::create_directories(imagesDir, ec);
    if (ec)
      throw std::runtime_error(imagesDir + ": cannot create folder");
    rawlogTmp = rl.string() + ".tmp";
    rawlog = std::make_unique<mrpt::io::CFileGZOutputStream>();
    if (!rawlog->open(rawlogTmp))
      throw std::runtime_error(*m_args.outputRawlog + ": cannot write");
  }

  CObservationProcessor processor(m_options);
  std::vector<TFrameResult> results;
  std::vector<CLandmarkScorer::TEvent> events, pointEvents;
  std::vector<std::size_t> eventRow;
  TSummary sum;
  {
    CFramePrefetcher frames(*source, m_args.maxFrames);
    while (auto frame = frames.next())
    {
      auto out = processor.process(*frame);
      const TFrameResult& r = out.result;
      sum.durationS += r.seconds;
      sum.cpuS += r.cpuSeconds;
      if (r.newLandmark)
      {
        const std::string png = (patchesDir / (frameName(r.frame) + ".png")).string();
        if (!cv::imwrite(png, processor.tracker().database().landmark(r.landmarkId).patch))
          throw std::runtime_error(png + ": cannot write");
      }
      if (r.status == ERoiStatus::Landmark)
      {
        events.push_back({r.frame, r.timestamp, r.landmarkId, r.newLandmark, r.roiPosition});
        pointEvents.push_back(
            {r.frame, r.timestamp, r.landmarkId, r.newLandmark, r.landmarkPosition});
        eventRow.push_back(results.size());
      }
      if (rawlog)
      {
        auto ar = mrpt::serialization::archiveFrom(*rawlog);
        ar << makeScan(*frame, imagesDir, m_options.observations.sensor_pose) << *out.observation;
      }
      results.push_back(r);
      if (results.size() % 50 == 0)
        progress(
            "frame " + std::to_string(results.size()) + "/" + std::to_string(source->size()) +
            ": " + std::to_string(processor.tracker().database().size()) + " landmarks, " +
            fmt(results.size() / std::max(sum.durationS, 1e-9), 1) + " fps");
    }
  }

  // Scores and counts.
  // The primary score uses [LandmarkScoring] recall_position; the other
  // definition is reported beside it (alternative_scoring).
  const bool pointPrimary = m_options.scoring.recall_position == "landmark_point";
  sum.recallPosition = m_options.scoring.recall_position;
  sum.altRecallPosition = pointPrimary ? "roi_median" : "landmark_point";
  std::optional<CLandmarkScorer::TScore> score, altScore;
  if (scorer)
  {
    score = scorer->score(pointPrimary ? pointEvents : events);
    altScore = scorer->score(pointPrimary ? events : pointEvents);
  }
  std::vector<std::string> outcome(results.size()), altOutcome(results.size());
  if (score)
    for (std::size_t i = 0; i < events.size(); ++i)
    {
      outcome[eventRow[i]] = toString(score->outcomes[i]);
      altOutcome[eventRow[i]] = toString(altScore->outcomes[i]);
    }

  long matches = 0, falseMatches = 0;
  for (const auto& r : results)
  {
    if (r.roi)
      ++sum.framesWithRoi;
    if (r.status == ERoiStatus::Landmark)
    {
      ++sum.confirmedRois;
      if (!r.newLandmark)
        ++sum.recalls;
    }
    matches += r.matches;
    falseMatches += r.falseMatches;
  }
  sum.frames = results.size();
  sum.landmarks = processor.tracker().database().size();
  if (sum.framesWithRoi)
  {
    sum.matchesPerFrame = double(matches) / sum.framesWithRoi;
    sum.falseMatchesPerFrame = double(falseMatches) / sum.framesWithRoi;
  }
  sum.fps = sum.durationS > 0 ? sum.frames / sum.durationS : 0;
  if (score)
  {
    sum.truePositives = score->truePositives;
    sum.falsePositives = score->falsePositives;
    sum.falseNegatives = score->falseNegatives;
    sum.unscored = score->unscored;
    sum.precision = score->precision;
    sum.recall = score->recall;
    sum.altFalsePositives = altScore->falsePositives;
    sum.altFalseNegatives = altScore->falseNegatives;
    sum.altPrecision = altScore->precision;
    sum.altRecall = altScore->recall;
  }

  // frames.csv
  std::ostringstream csv;
  csv << "frame,timestamp,status,landmark,new,matches,false_matches,seconds,features,"
         "roi_features,depth_valid,depth_mean_m,depth_median_m,roi_x,roi_y,roi_w,roi_h,"
         "recall_inliers,candidates,roi_pos_x,roi_pos_y,roi_pos_z,lm_x,lm_y,lm_w,lm_h,lm_pos_x,"
         "lm_pos_y,lm_pos_z,rigid_pairs,rigid_rms_m,cpu_seconds,s_roi,s_features,s_confirm,s_query,"
         "score,alt_score\n";
  for (std::size_t i = 0; i < results.size(); ++i)
  {
    const auto& r = results[i];
    csv << r.frame << ',' << fmt(r.timestamp, 6) << ',' << r.statusText() << ',' << r.landmarkId
        << ',' << (r.newLandmark ? 1 : 0) << ',' << r.matches << ',' << r.falseMatches << ','
        << fmt(r.seconds, 5) << ',' << r.features << ',' << r.roiFeatures << ',' << r.depthValid
        << ',' << fmt(r.depthMean) << ',' << fmt(r.depthMedian) << ',';
    if (r.roi)
      csv << r.roi->x << ',' << r.roi->y << ',' << r.roi->width << ',' << r.roi->height;
    else
      csv << ",,,";
    csv << ',' << r.recallInliers << ',' << r.candidates << ',';
    auto point = [&](const std::optional<mrpt::math::TPoint3D>& p)
    {
      if (p)
        csv << fmt(p->x) << ',' << fmt(p->y) << ',' << fmt(p->z);
      else
        csv << ",,";
    };
    point(r.roiPosition);
    csv << ',';
    if (r.landmarkBox)
      csv << r.landmarkBox->x << ',' << r.landmarkBox->y << ',' << r.landmarkBox->width << ','
          << r.landmarkBox->height;
    else
      csv << ",,,";
    csv << ',';
    point(r.landmarkPosition);
    csv << ',' << r.rigidInliers << ',' << fmt(r.rigidRms) << ',' << fmt(r.cpuSeconds, 5) << ','
        << fmt(r.secondsRoi, 5) << ',' << fmt(r.secondsFeatures, 5) << ','
        << fmt(r.secondsConfirm, 5) << ',' << fmt(r.secondsQuery, 5) << ',' << outcome[i] << ','
        << altOutcome[i] << '\n';
  }
  writeTextAtomically((outDir / "frames.csv").string(), csv.str());

  processor.tracker().database().save((outDir / "landmarks.db").string());

  if (rawlog)
  {
    rawlog->close();
    rawlog.reset();
    fs::rename(rawlogTmp, rawlogTmp.substr(0, rawlogTmp.size() - 4), ec);
    if (ec)
      throw std::runtime_error(*m_args.outputRawlog + ": cannot write: " + ec.message());
  }

  sum.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  nlohmann::json j;
  j["input"] = m_args.input;
  j["sequence"] = source->name();
  j["feature"] = features::toString(m_options.features.feature_type);
  j["max_features"] = m_options.features.max_features;
  j["roi_preset"] = m_options.roi.preset;
  j["ground_truth"] = scorer ? nlohmann::json(*gtFile) : nlohmann::json(nullptr);
  j["match_radius"] = m_options.scoring.match_radius;
  j["frames"] = sum.frames;
  j["frames_with_roi"] = sum.framesWithRoi;
  j["confirmed_rois"] = sum.confirmedRois;
  j["landmarks"] = sum.landmarks;
  j["recalls"] = sum.recalls;
  j["true_positives"] = orNull(sum.truePositives);
  j["false_positives"] = orNull(sum.falsePositives);
  j["false_negatives"] = orNull(sum.falseNegatives);
  j["unscored"] = orNull(sum.unscored);
  j["precision"] = orNull(sum.precision);
  j["recall"] = orNull(sum.recall);
  j["recall_position"] = sum.recallPosition;
  if (altScore)
  {
    j["alternative_scoring"] = {{"recall_position", sum.altRecallPosition},
                                {"true_positives", altScore->truePositives},
                                {"false_positives", altScore->falsePositives},
                                {"false_negatives", altScore->falseNegatives},
                                {"precision", orNull(altScore->precision)},
                                {"recall", orNull(altScore->recall)}};
  }
  else
    j["alternative_scoring"] = nullptr;
  j["matches_per_frame"] = sum.matchesPerFrame;
  j["false_matches_per_frame"] = sum.falseMatchesPerFrame;
  j["duration_s"] = sum.durationS;
  j["fps"] = sum.fps;
  // Calling thread only: OpenCV's worker threads (SIFT) are not included.
  j["cpu_s_main_thread"] = sum.cpuS;
  j["wall_s"] = sum.wallS;
  j["fps_wall"] = sum.wallS > 0 ? sum.frames / sum.wallS : 0;
  writeTextAtomically((outDir / "summary.json").string(), j.dump(2) + "\n");
  folder.commit();

  std::ostringstream done;
  done << "done: " << sum.frames << " frames, " << sum.landmarks << " landmarks, " << sum.recalls
       << " recalls";
  if (score)
    done << ", TP " << score->truePositives << " FP " << score->falsePositives << " FN "
         << score->falseNegatives << ", precision " << fmt(sum.precision.value_or(NAN), 3)
         << " recall " << fmt(sum.recall.value_or(NAN), 3) << " (" << sum.recallPosition << "; "
         << sum.altRecallPosition << ": TP " << altScore->truePositives << " FP "
         << altScore->falsePositives << " FN " << altScore->falseNegatives << ")";
  done << ", " << fmt(sum.fps, 1) << " fps (pipeline), " << fmt(sum.wallS, 1) << " s wall";
  progress(done.str());
  return sum;
}
}  // namespace roislam::landmarks
