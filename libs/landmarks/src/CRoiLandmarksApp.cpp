#include "roislam/landmarks/CRoiLandmarksApp.h"

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>
#include <roislam/common/JsonOrNull.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "roislam/common/COutputFolder.h"
#include "roislam/common/TextFiles.h"
#include "roislam/io/CFramePrefetcher.h"
#include "roislam/io/CFrameSource.h"
#include "roislam/io/ObservationConversion.h"
#include "roislam/io/TumTrajectory.h"
#include "roislam/kfslam/CKfSlamSession.h"
#include "roislam/landmarks/CLandmarkScorer.h"
#include "roislam/landmarks/CObservationProcessor.h"

namespace fs = std::filesystem;

namespace roislam::landmarks
{
namespace
{

std::string frameName(uint64_t frame)
{
  std::ostringstream os;
  os << std::setw(6) << std::setfill('0') << frame;
  return os.str();
}

/** An RGB-D observation for the annotated rawlog: raw TUM-scaled depth in an
 *  external .bin, the colour image external (the source PNG when it exists,
 *  else a PNG written next to the depth). */
mrpt::obs::CObservation3DRangeScan::Ptr makeScan(
    const io::TRGBDFrame& f, const std::string& imagesDir, const mrpt::poses::CPose3D& sensorPose)
{
  auto obs = io::frameToObservation(f);
  obs->sensorPose = sensorPose;
  const std::string name = frameName(f.index);
  std::error_code ec;
  if (!f.rgbSource.empty() && fs::is_regular_file(f.rgbSource, ec))
    obs->intensityImage.setExternalStorage(fs::absolute(f.rgbSource).string());
  else
  {
    const std::string png = imagesDir + "/" + name + "_rgb.png";
    if (!cv::imwrite(png, f.rgb))
      throw std::runtime_error(png + ": cannot write");
    obs->intensityImage.setExternalStorage(name + "_rgb.png");
  }
  obs->rangeImage_convertToExternalStorage(name + "_depth.bin", imagesDir + "/");
  return obs;
}

std::string fmt(double v, int precision = 4)
{
  if (!std::isfinite(v))
    return "nan";
  std::ostringstream os;
  os << std::fixed << std::setprecision(precision) << v;
  return os.str();
}

/** The annotated rawlog (--output-rawlog), written to a temporary name and
 *  renamed by commitAnnotatedRawlog(). */
struct TAnnotatedRawlog
{
  std::string file, tmp, imagesDir;
  std::string label;  //!< the name given on the command line, for errors
  std::unique_ptr<mrpt::io::CFileGZOutputStream> stream;
};

/** `file` relative to `dir` when it lies inside it. */
std::optional<fs::path> pathInside(const std::string& file, const std::string& dir)
{
  const fs::path rel = fs::absolute(file).lexically_normal().lexically_relative(
      fs::absolute(dir).lexically_normal());
  if (rel.empty() || *rel.begin() == "..")
    return std::nullopt;
  return rel;
}

/** Opens the annotated rawlog `label` at `file` (inside the staging folder
 *  when `label` lies inside the output folder). */
TAnnotatedRawlog openAnnotatedRawlog(
    const std::optional<std::string>& file, const std::string& label)
{
  TAnnotatedRawlog out;
  if (!file)
    return out;
  std::error_code ec;
  const fs::path rl(*file);
  out.file = *file;
  out.label = label;
  out.imagesDir = (rl.parent_path() / (rl.stem().string() + "_Images")).string();
  if (rl.has_parent_path())
    fs::create_directories(rl.parent_path(), ec);
  fs::create_directories(out.imagesDir, ec);
  if (ec)
    throw std::runtime_error(out.imagesDir + ": cannot create folder");
  out.tmp = *file + ".tmp";
  out.stream = std::make_unique<mrpt::io::CFileGZOutputStream>();
  if (!out.stream->open(out.tmp))
    throw std::runtime_error(label + ": cannot write");
  return out;
}

void commitAnnotatedRawlog(TAnnotatedRawlog& rawlog)
{
  if (!rawlog.stream)
    return;
  rawlog.stream->close();
  rawlog.stream.reset();
  std::error_code ec;
  fs::rename(rawlog.tmp, rawlog.file, ec);
  if (ec)
    throw std::runtime_error(rawlog.label + ": cannot write: " + ec.message());
}

/** What the frame loop collects: every frame's record and the confirmed ROI
 *  events for scoring, with both recall positions (ROI median, landmark
 *  point) and the frames.csv row of each event. */
struct TFrameLog
{
  std::vector<TFrameResult> results;
  std::vector<CLandmarkScorer::TEvent> roiEvents, pointEvents;
  std::vector<std::size_t> eventRow;
  double durationS = 0, cpuS = 0;

  void add(const TFrameResult& r)
  {
    durationS += r.seconds;
    cpuS += r.cpuSeconds;
    if (r.status == ERoiStatus::Landmark)
    {
      roiEvents.push_back({r.frame, r.timestamp, r.landmarkId, r.newLandmark, r.roiPosition});
      pointEvents.push_back(
          {r.frame, r.timestamp, r.landmarkId, r.newLandmark, r.landmarkPosition});
      eventRow.push_back(results.size());
    }
    results.push_back(r);
  }
};

/** The ground-truth scores of the events and each frame's outcome text
 *  (empty for frames without an event), primary and alternative. */
struct TScores
{
  std::optional<CLandmarkScorer::TScore> primary, alternative;
  std::vector<std::string> outcome, altOutcome;
};

TScores scoreEvents(
    const TFrameLog& log, const std::optional<CLandmarkScorer>& scorer, bool pointPrimary)
{
  TScores s;
  s.outcome.resize(log.results.size());
  s.altOutcome.resize(log.results.size());
  if (!scorer)
    return s;
  s.primary = scorer->score(pointPrimary ? log.pointEvents : log.roiEvents);
  s.alternative = scorer->score(pointPrimary ? log.roiEvents : log.pointEvents);
  for (std::size_t i = 0; i < log.roiEvents.size(); ++i)
  {
    s.outcome[log.eventRow[i]] = toString(s.primary->outcomes[i]);
    s.altOutcome[log.eventRow[i]] = toString(s.alternative->outcomes[i]);
  }
  return s;
}

/** Counts, rates and scores of the summary (everything but the wall time). */
void summarize(
    const TFrameLog& log, const TScores& scores, std::size_t landmarks,
    CRoiLandmarksApp::TSummary& sum)
{
  sum.durationS = log.durationS;
  sum.cpuS = log.cpuS;
  long matches = 0, falseMatches = 0;
  for (const auto& r : log.results)
  {
    if (r.roi)
      ++sum.framesWithRoi;
    if (r.rejectedByHue)
      ++sum.framesRejectedByHue;
    if (r.status == ERoiStatus::Landmark)
    {
      ++sum.confirmedRois;
      if (!r.newLandmark)
        ++sum.recalls;
    }
    matches += r.matches;
    falseMatches += r.falseMatches;
  }
  sum.frames = log.results.size();
  sum.landmarks = landmarks;
  if (sum.framesWithRoi)
  {
    sum.matchesPerFrame = double(matches) / sum.framesWithRoi;
    sum.falseMatchesPerFrame = double(falseMatches) / sum.framesWithRoi;
  }
  sum.fps = sum.durationS > 0 ? sum.frames / sum.durationS : 0;
  if (!scores.primary)
    return;
  const auto& p = *scores.primary;
  const auto& a = *scores.alternative;
  sum.truePositives = p.truePositives;
  sum.falsePositives = p.falsePositives;
  sum.falseNegatives = p.falseNegatives;
  sum.unscored = p.unscored;
  sum.precision = p.precision;
  sum.recall = p.recall;
  sum.altFalsePositives = a.falsePositives;
  sum.altFalseNegatives = a.falseNegatives;
  sum.altPrecision = a.precision;
  sum.altRecall = a.recall;
}

void csvPoint(std::ostream& csv, const std::optional<mrpt::math::TPoint3D>& p)
{
  if (p)
    csv << fmt(p->x) << ',' << fmt(p->y) << ',' << fmt(p->z);
  else
    csv << ",,";
}

void csvBox(std::ostream& csv, const std::optional<cv::Rect>& b)
{
  if (b)
    csv << b->x << ',' << b->y << ',' << b->width << ',' << b->height;
  else
    csv << ",,,";
}

void csvRow(
    std::ostream& csv, const TFrameResult& r, const std::string& outcome,
    const std::string& altOutcome)
{
  csv << r.frame << ',' << fmt(r.timestamp, 6) << ',' << r.statusText() << ',' << r.landmarkId
      << ',' << (r.newLandmark ? 1 : 0) << ',' << r.matches << ',' << r.falseMatches << ','
      << fmt(r.seconds, 5) << ',' << r.features << ',' << r.roiFeatures << ',' << r.depthValid
      << ',' << fmt(r.depthMean) << ',' << fmt(r.depthMedian) << ',';
  csvBox(csv, r.roi);
  csv << ',' << r.recallInliers << ',' << r.candidates << ',';
  csvPoint(csv, r.roiPosition);
  csv << ',';
  csvBox(csv, r.landmarkBox);
  csv << ',';
  csvPoint(csv, r.landmarkPosition);
  csv << ',' << r.rigidInliers << ',' << fmt(r.rigidRms) << ',' << fmt(r.cpuSeconds, 5) << ','
      << fmt(r.secondsRoi, 5) << ',' << fmt(r.secondsFeatures, 5) << ',' << fmt(r.secondsConfirm, 5)
      << ',' << fmt(r.secondsQuery, 5) << ',' << outcome << ',' << altOutcome << '\n';
}

std::string framesCsv(const TFrameLog& log, const TScores& scores)
{
  std::ostringstream csv;
  csv << "frame,timestamp,status,landmark,new,matches,false_matches,seconds,features,"
         "roi_features,depth_valid,depth_mean_m,depth_median_m,roi_x,roi_y,roi_w,roi_h,"
         "recall_inliers,candidates,roi_pos_x,roi_pos_y,roi_pos_z,lm_x,lm_y,lm_w,lm_h,lm_pos_x,"
         "lm_pos_y,lm_pos_z,rigid_pairs,rigid_rms_m,cpu_seconds,s_roi,s_features,s_confirm,s_query,"
         "score,alt_score\n";
  for (std::size_t i = 0; i < log.results.size(); ++i)
    csvRow(csv, log.results[i], scores.outcome[i], scores.altOutcome[i]);
  return csv.str();
}

nlohmann::json alternativeJson(const CRoiLandmarksApp::TSummary& sum, const TScores& scores)
{
  if (!scores.alternative)
    return nullptr;
  const auto& a = *scores.alternative;
  return {{"recall_position", sum.altRecallPosition},     {"true_positives", a.truePositives},
          {"false_positives", a.falsePositives},          {"false_negatives", a.falseNegatives},
          {"precision", common::jsonOrNull(a.precision)}, {"recall", common::jsonOrNull(a.recall)}};
}

/** What the run was: input, extractor, ROI preset, ground truth. */
nlohmann::json runJson(
    const CRoiLandmarksApp::TArguments& args, const TPipelineOptions& options,
    const std::string& sequence, const std::optional<std::string>& gtFile)
{
  nlohmann::json j;
  j["input"] = args.input;
  j["sequence"] = sequence;
  j["feature"] = features::toString(options.features.feature_type);
  j["max_features"] = options.features.max_features;
  j["roi_preset"] = options.roi.preset;
  j["verify_hue"] = options.roi.verify_hue;
  j["ground_truth"] = gtFile ? nlohmann::json(*gtFile) : nlohmann::json(nullptr);
  j["match_radius"] = options.scoring.match_radius;
  return j;
}

nlohmann::json summaryJson(
    nlohmann::json j, const CRoiLandmarksApp::TSummary& sum, const TScores& scores)
{
  j["frames"] = sum.frames;
  j["frames_with_roi"] = sum.framesWithRoi;
  j["frames_rejected_by_hue"] = sum.framesRejectedByHue;
  j["confirmed_rois"] = sum.confirmedRois;
  j["landmarks"] = sum.landmarks;
  j["recalls"] = sum.recalls;
  j["true_positives"] = common::jsonOrNull(sum.truePositives);
  j["false_positives"] = common::jsonOrNull(sum.falsePositives);
  j["false_negatives"] = common::jsonOrNull(sum.falseNegatives);
  j["unscored"] = common::jsonOrNull(sum.unscored);
  j["precision"] = common::jsonOrNull(sum.precision);
  j["recall"] = common::jsonOrNull(sum.recall);
  j["recall_position"] = sum.recallPosition;
  j["alternative_scoring"] = alternativeJson(sum, scores);
  j["matches_per_frame"] = sum.matchesPerFrame;
  j["false_matches_per_frame"] = sum.falseMatchesPerFrame;
  j["duration_s"] = sum.durationS;
  j["fps"] = sum.fps;
  // Calling thread only: OpenCV's worker threads (SIFT) are not included.
  j["cpu_s_main_thread"] = sum.cpuS;
  j["wall_s"] = sum.wallS;
  j["fps_wall"] = sum.wallS > 0 ? sum.frames / sum.wallS : 0;
  return j;
}

std::string kfSlamLine(const nlohmann::json& k)
{
  const auto m = [&](const char* key)
  { return k.contains(key) && k[key].is_number() ? fmt(k[key].get<double>()) : "n/a"; };
  return "kf-slam: " + std::to_string(k.value("landmarks", 0)) + " landmarks, " +
         std::to_string(k.value("measurements", 0)) + " measurements; ATE RMSE " + m("ate_rmse") +
         " m (odometry alone " + m("odometry_ate_rmse") + " m), RPE " + m("rpe_trans_rmse") +
         " m / " + m("rpe_rot_rmse_deg") + " deg (odometry " + m("odometry_rpe_trans_rmse") +
         " m / " + m("odometry_rpe_rot_rmse_deg") + " deg)";
}

std::string doneLine(const CRoiLandmarksApp::TSummary& sum, const TScores& scores)
{
  std::ostringstream done;
  done << "done: " << sum.frames << " frames, " << sum.landmarks << " landmarks, " << sum.recalls
       << " recalls";
  if (scores.primary)
  {
    const auto& p = *scores.primary;
    const auto& a = *scores.alternative;
    done << ", TP " << p.truePositives << " FP " << p.falsePositives << " FN " << p.falseNegatives
         << ", precision " << fmt(sum.precision.value_or(NAN), 3) << " recall "
         << fmt(sum.recall.value_or(NAN), 3) << " (" << sum.recallPosition << "; "
         << sum.altRecallPosition << ": TP " << a.truePositives << " FP " << a.falsePositives
         << " FN " << a.falseNegatives << ")";
  }
  done << ", " << fmt(sum.fps, 1) << " fps (pipeline), " << fmt(sum.wallS, 1) << " s wall";
  return done.str();
}

/** The frame loop: every frame through the observation processor, new
 *  landmarks' patches saved, the annotated rawlog written. */
TFrameLog processFrames(
    io::CFrameSource& source, std::size_t maxFrames, CObservationProcessor& processor,
    const mrpt::poses::CPose3D& sensorPose, const fs::path& patchesDir, TAnnotatedRawlog& rawlog,
    kfslam::CKfSlamSession* kfSlam, const std::function<void(const std::string&)>& progress)
{
  TFrameLog log;
  // Decoding a frame costs about as much as the ORB pipeline: a few ahead.
  io::CFramePrefetcher<> frames(source, 4, {}, maxFrames);
  while (auto item = frames.next())
  {
    const io::TRGBDFrame* frame = &item->frame;
    auto out = processor.process(*frame);
    const TFrameResult& r = out.result;
    if (r.newLandmark)
    {
      const std::string png = (patchesDir / (frameName(r.frame) + ".png")).string();
      if (!cv::imwrite(png, processor.tracker().database().landmark(r.landmarkId).patch))
        throw std::runtime_error(png + ": cannot write");
    }
    if (rawlog.stream)
    {
      auto ar = mrpt::serialization::archiveFrom(*rawlog.stream);
      ar << *makeScan(*frame, rawlog.imagesDir, sensorPose) << *out.observation;
    }
    if (kfSlam)
      kfSlam->addFrame(*frame, *out.observation);
    log.add(r);
    if (log.results.size() % 50 == 0 && progress)
      progress(
          "frame " + std::to_string(log.results.size()) + "/" + std::to_string(source.size()) +
          ": " + std::to_string(processor.tracker().database().size()) + " landmarks, " +
          fmt(log.results.size() / std::max(log.durationS, 1e-9), 1) + " fps");
  }
  return log;
}

// --------------------------------------------------------------- run stages

fs::path createPatchesFolder(const fs::path& outDir)
{
  const fs::path patchesDir = outDir / "landmarks";
  std::error_code ec;
  fs::create_directories(patchesDir, ec);
  if (ec)
    throw std::runtime_error(patchesDir.string() + ": cannot create folder");
  return patchesDir;
}

std::optional<io::TTrajectory> loadGroundTruth(const std::optional<std::string>& gtFile)
{
  if (gtFile && fs::is_regular_file(*gtFile))
    return io::loadTumTrajectory(*gtFile);
  return std::nullopt;
}

/** The annotated rawlog, staged in outDir when it is to end up inside it. */
TAnnotatedRawlog openRunRawlog(
    const CRoiLandmarksApp::TArguments& args, const fs::path& outDir,
    const std::optional<fs::path>& rawlogInFolder)
{
  return openAnnotatedRawlog(
      rawlogInFolder ? std::optional<std::string>((outDir / *rawlogInFolder).string())
                     : args.outputRawlog,
      args.outputRawlog.value_or(""));
}

std::string startLine(
    const io::CFrameSource& source, const TPipelineOptions& options,
    const std::optional<std::string>& gtFile, bool scored)
{
  return "roi-landmarks: " + source.name() + ", " + std::to_string(source.size()) + " frames, " +
         features::toString(options.features.feature_type) + ", ROI preset " + options.roi.preset +
         (scored ? ", ground truth " + *gtFile : ", no ground truth");
}

struct TScoredRun
{
  CRoiLandmarksApp::TSummary sum;
  TScores scores;
};

TScoredRun scoreRun(
    const TFrameLog& log, const std::optional<CLandmarkScorer>& scorer,
    const std::string& recallPosition, std::size_t landmarks)
{
  // The primary score uses [LandmarkScoring] recall_position; the other
  // definition is reported beside it (alternative_scoring).
  const bool pointPrimary = recallPosition == "landmark_point";
  TScoredRun r;
  r.sum.recallPosition = recallPosition;
  r.sum.altRecallPosition = pointPrimary ? "roi_median" : "landmark_point";
  r.scores = scoreEvents(log, scorer, pointPrimary);
  summarize(log, r.scores, landmarks, r.sum);
  return r;
}

void writeSummaryJson(
    const fs::path& outDir, const CRoiLandmarksApp::TArguments& args,
    const TPipelineOptions& options, const io::CFrameSource& source,
    const std::optional<std::string>& gtFile, const TScoredRun& run, bool kfSlam)
{
  auto j = summaryJson(runJson(args, options, source.name(), gtFile), run.sum, run.scores);
  j["sensor"] = source.sensor().toJson();
  if (const auto clock = source.frameClock())
    j["sensor"]["frame_clock"] = io::toJson(*clock);
  if (kfSlam)
    j["kf_slam"] = run.sum.kfSlam;
  common::writeFileAtomically((outDir / "summary.json").string(), j.dump(2) + "\n");
}
}  // namespace

const std::vector<std::string>& CRoiLandmarksApp::outputFiles()
{
  static const std::vector<std::string> names{
      "frames.csv",
      "landmarks",
      "landmarks.db",
      "summary.json",
      "kf-slam",
      "kf-slam.rawlog",
      "kf-slam.landmarks_gt.txt"};
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

kfslam::CKfSlamSession::TSetup CRoiLandmarksApp::kfSlamSetup(
    const io::CFrameSource& source, const std::string& outputDir,
    const std::string& finalOutputDir) const
{
  kfslam::CKfSlamSession::TSetup s;
  s.options = m_options.kfSlam;
  s.iniDir =
      m_args.iniFile.empty() ? std::string() : fs::path(m_args.iniFile).parent_path().string();
  s.sensorPose = m_options.observations.sensor_pose;
  s.outputDir = outputDir;
  s.finalOutputDir = finalOutputDir;
  if (m_args.feature)
    s.feature = m_options.features.feature_type;
  s.maxFeatures = m_args.maxFeatures;
  s.sensor = source.sensor().sensor;
  return s;
}

void CRoiLandmarksApp::progress(const std::string& line) const
{
  if (m_args.progress)
    m_args.progress(line);
}

CRoiLandmarksApp::TSummary CRoiLandmarksApp::run()
{
  const auto wall0 = std::chrono::steady_clock::now();
  // Complete or absent: everything goes to a staging folder renamed at the end.
  const auto rawlogInFolder = m_args.outputRawlog
                                  ? pathInside(*m_args.outputRawlog, m_args.outputDir)
                                  : std::optional<fs::path>();
  common::COutputFolder folder(m_args.outputDir, outputFolderOptions(rawlogInFolder));
  const fs::path outDir(folder.path());
  const fs::path patchesDir = createPatchesFolder(outDir);

  auto source = io::CFrameSource::open(m_args.input, m_args.camera);
  std::optional<CLandmarkScorer> scorer;
  const auto gtFile = source->groundTruthFile();
  const std::optional<io::TTrajectory> gt = loadGroundTruth(gtFile);
  if (gt)
    scorer.emplace(m_options.scoring, *gt);
  progress(startLine(*source, m_options, gtFile, scorer.has_value()));
  progress("roi-landmarks: " + source->sensor().summary());

  TAnnotatedRawlog rawlog = openRunRawlog(m_args, outDir, rawlogInFolder);
  auto kfSlam = m_args.kfSlam ? std::make_unique<kfslam::CKfSlamSession>(
                                    kfSlamSetup(*source, outDir.string(), folder.target()))
                              : nullptr;
  CObservationProcessor processor(m_options);
  const TFrameLog log = processFrames(
      *source, m_args.maxFrames, processor, m_options.observations.sensor_pose, patchesDir, rawlog,
      kfSlam.get(), m_args.progress);

  TScoredRun run = scoreRun(
      log, scorer, m_options.scoring.recall_position, processor.tracker().database().size());
  TSummary& sum = run.sum;
  common::writeFileAtomically((outDir / "frames.csv").string(), framesCsv(log, run.scores));
  processor.tracker().database().save((outDir / "landmarks.db").string());
  commitAnnotatedRawlog(rawlog);

  if (kfSlam)
  {
    progress(
        "roi-landmarks: running MRPT's EKF-SLAM (CRangeBearingKFSLAM) on " +
        (fs::path(m_args.outputDir) / fs::path(kfSlam->rawlogFile()).filename()).string());
    sum.kfSlam = kfSlam->finish(gt);
    progress(kfSlamLine(sum.kfSlam));
  }
  sum.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  writeSummaryJson(outDir, m_args, m_options, *source, gtFile, run, kfSlam != nullptr);
  folder.commit();
  progress(doneLine(sum, run.scores));
  return sum;
}

}  // namespace roislam::landmarks
