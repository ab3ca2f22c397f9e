/* roi-graphslam's outputs are complete or absent, and every malformed input is
 * a one-line error: the ini ("[this is not"), a non-empty output
 * folder (refused; --overwrite replaces an earlier output without leaving its
 * stale files), a failed evaluation (NaN in the ground truth: recorded in
 * summary.json, exit 3 unless --allow-partial), and a failure injected while
 * the map is written (the folder stays absent, or exactly as before). */
#include <gtest/gtest.h>
#include <roislam/graphslam/CSlamOutputWriter.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/testing/FolderListing.h>
#include <roislam/testing/TestData.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
namespace graphslam = roislam::graphslam;

namespace
{
struct TRun
{
  int exitCode = -1;
  std::string err;
};

TRun runApp(const std::string& args)
{
  const std::string exe = roislam::testing::binaryDir() + "/apps/roi-graphslam/roi-graphslam";
  const std::string errFile = roislam::testing::makeTempDir("gs_rel_err") + "/stderr.txt";
  const int rc = std::system((exe + " " + args + " > /dev/null 2> " + errFile).c_str());
  TRun r;
  r.exitCode = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  std::ifstream f(errFile);
  std::stringstream ss;
  ss << f.rdbuf();
  r.err = ss.str();
  fs::remove_all(fs::path(errFile).parent_path());
  return r;
}

std::string lastLine(const std::string& s)
{
  std::string t = s;
  while (!t.empty() && t.back() == '\n')
    t.pop_back();
  return t.substr(t.rfind('\n') == std::string::npos ? 0 : t.rfind('\n') + 1);
}

std::string readFile(const fs::path& p)
{
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/** A TUM folder sharing `seq`'s images and lists (symlinks) with its own
 *  ground truth text. */
std::string withGroundTruth(const std::string& seq, const std::string& root, const std::string& gt)
{
  const fs::path dir = fs::path(root) / "seq";
  fs::create_directories(dir);
  for (const char* e : {"rgb", "depth", "rgb.txt", "depth.txt", "camera.ini"})
    fs::create_symlink(fs::path(seq) / e, dir / e);
  std::ofstream(dir / "groundtruth.txt") << gt;
  return dir.string();
}
}  // namespace

TEST(OutputReliability, MalformedIniIsAnErrorNotTheDefaults)
{
  const std::string tmp = roislam::testing::makeTempDir("gs_rel_ini");
  const std::string ini = tmp + "/bad.ini";
  std::ofstream(ini) << "[this is not";
  const auto r = runApp("--ini " + ini + " --input /nonexistent --output-dir " + tmp + "/out");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(
      r.err, "roi-graphslam: error: " + ini + ":1: malformed section header '[this is not'\n");
  std::ofstream(ini) << "[FrontEnd]\nmode = roi_big\nmode = traditional\n";
  const auto d = runApp("--ini " + ini + " --input /nonexistent --output-dir " + tmp + "/out");
  EXPECT_EQ(d.exitCode, 1);
  EXPECT_EQ(
      d.err, "roi-graphslam: error: " + ini + ":3: duplicate key 'mode' (first given on line 2)\n");
  std::ofstream(ini) << "[FrontEnd]\nmode = roi_big\nthis is garbage\n";
  const auto g = runApp("--ini " + ini + " --input /nonexistent --output-dir " + tmp + "/out");
  EXPECT_EQ(g.exitCode, 1);
  EXPECT_EQ(
      g.err, "roi-graphslam: error: " + ini +
                 ":3: expected a comment, [section] or key = value, got 'this is garbage'\n");
  EXPECT_FALSE(fs::exists(tmp + "/out"));
  fs::remove_all(tmp);
}

TEST(OutputReliability, NonEmptyFolderRefusedAndOverwriteLeavesNoStaleFile)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "featureless");
  const std::string tmp = roislam::testing::makeTempDir("gs_rel_overwrite");
  const std::string out = tmp + "/out";
  const std::string common = "--input " + seq + " --output-dir " + out + " --max-frames 40";

  // A folder with a file we do not write: refused, with or without --overwrite.
  fs::create_directories(out);
  std::ofstream(out + "/notes.txt") << "precious";
  auto r = runApp(common);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(
      lastLine(r.err), "roi-graphslam: error: output dir " + out +
                           ": not empty (holds notes.txt); use --overwrite to replace an earlier "
                           "output");
  r = runApp(common + " --overwrite");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("holds notes.txt, which this app does not write"), std::string::npos)
      << r.err;
  EXPECT_EQ(roislam::testing::outputListing(out), std::vector<std::string>{"notes.txt"});
  fs::remove(out + "/notes.txt");

  // A first run with a snapshot, then --no-snapshot: refused without
  // --overwrite; with it, the old snapshot.png is gone.
  r = runApp(common + " --allow-partial");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_TRUE(fs::exists(out + "/snapshot.png"));
  const std::string firstSummary = readFile(out + "/summary.json");
  r = runApp(common + " --no-snapshot --allow-partial");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(readFile(out + "/summary.json"), firstSummary);
  r = runApp(common + " --no-snapshot --allow-partial --overwrite");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_FALSE(fs::exists(out + "/snapshot.png"));
  EXPECT_TRUE(fs::exists(out + "/summary.json"));
  // Nothing but the output folder is left beside it (no staging folder).
  EXPECT_EQ(roislam::testing::outputListing(tmp), std::vector<std::string>{"out"});
  fs::remove_all(tmp);
}

TEST(OutputReliability, UnwritableOutputFolderFailsBeforeTheRun)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "featureless");
  const std::string tmp = roislam::testing::makeTempDir("gs_rel_unwritable");
  std::ofstream(tmp + "/file") << "x";
  const auto r = runApp("--input " + seq + " --output-dir " + tmp + "/file/out");
  EXPECT_EQ(r.exitCode, 1);
  // One line, and no progress line: the folder was checked before the run.
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("roi-graphslam: error: output dir " + tmp + "/file/out: ", 0), 0u) << r.err;
  fs::remove_all(tmp);
}

TEST(OutputReliability, FailedEvaluationIsRecordedWithItsOwnExitStatus)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "featureless");
  const std::string tmp = roislam::testing::makeTempDir("gs_rel_eval");
  // The generated ground truth with a NaN on its third data line.
  std::istringstream gtIn(readFile(fs::path(seq) / "groundtruth.txt"));
  std::string gt, line;
  int data = 0, nanLine = 0, lineNo = 0;
  while (std::getline(gtIn, line))
  {
    ++lineNo;
    if (!line.empty() && line[0] != '#' && ++data == 3)
    {
      line = line.substr(0, line.find(' ')) + " nan 0 0 0 0 0 1";
      nanLine = lineNo;
    }
    gt += line + "\n";
  }
  const std::string input = withGroundTruth(seq, tmp, gt);
  const std::string out = tmp + "/out";
  auto r = runApp("--input " + input + " --output-dir " + out + " --no-snapshot");
  EXPECT_EQ(r.exitCode, 3) << r.err;
  EXPECT_NE(lastLine(r.err).find("incomplete outputs in " + out), std::string::npos) << r.err;
  auto s = nlohmann::json::parse(readFile(out + "/summary.json"));
  EXPECT_TRUE(s["partial"].get<bool>());
  EXPECT_TRUE(s["ate_rmse"].is_null());
  const std::string where = input + "/groundtruth.txt:" + std::to_string(nanLine) + ": NaN value";
  EXPECT_NE(s["evaluation_error"].get<std::string>().find(where), std::string::npos)
      << s["evaluation_error"];
  ASSERT_EQ(s["incomplete"].size(), 1u);
  // The rest of the outputs is there.
  for (const char* f : {"trajectory.txt", "graph.graph", "map.bt", "frames.csv"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;

  r = runApp(
      "--input " + input + " --output-dir " + out + " --no-snapshot --overwrite --allow-partial");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  s = nlohmann::json::parse(readFile(out + "/summary.json"));
  EXPECT_TRUE(s["partial"].get<bool>());
  fs::remove_all(tmp);
}

TEST(OutputReliability, FailureWhileWritingTheMapLeavesTheFolderAbsentOrAsBefore)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  graphslam::CSlamContext::TConfig cfg;
  cfg.frontEnd.extractor.feature_type = roislam::features::EFeatureType::ORB;
  graphslam::CSlamPipeline p(cfg, roislam::io::CFrameSource::open(seq));
  while (p.records().size() < 30 && p.step())
  {
  }
  p.finish();
  ASSERT_GE(p.context().keyframeClouds().size(), 2u);

  const std::string tmp = roislam::testing::makeTempDir("gs_rel_map");
  const auto writeAll = [&](const std::string& dir, bool overwrite, bool failInMap)
  {
    graphslam::CSlamOutputWriter writer(dir, overwrite);
    writer.writeTrajectory(p.trajectory(), "test");
    writer.writeGraph(p.graph());
    writer.writeFramesCsv(p.records());
    std::size_t calls = 0;
    const graphslam::CSlamOutputWriter::TRun run{
        p.records(), p.context(), p.graph(),
        [&](std::size_t id)
        {
          // Injected failure half way through the map's keyframes.
          if (failInMap && ++calls == 2)
            throw std::runtime_error("injected failure while writing map.bt");
          return p.keyframePose(id);
        }};
    const auto content = writer.writeMap(run, mrpt::poses::CPose3D());
    writer.writeScene(content, false);
    writer.writeSummary({{"frames", p.records().size()}});
  };

  // No earlier output: absent after the failure.
  const std::string out = tmp + "/out";
  EXPECT_THROW(writeAll(out, false, true), std::runtime_error);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(fs::is_empty(tmp));

  // An earlier output, replaced with --overwrite: untouched after the failure.
  writeAll(out, false, false);
  const auto before = roislam::testing::outputListing(out);
  EXPECT_EQ(
      before, (std::vector<std::string>{
                  "frames.csv", "graph.graph", "map.bt", "scene.3Dscene", "summary.json",
                  "trajectory.txt"}));
  std::map<std::string, std::string> contents;
  for (const auto& f : before)
    contents[f] = readFile(fs::path(out) / f);
  std::ofstream(fs::path(out) / "snapshot.png") << "an earlier snapshot";
  EXPECT_THROW(writeAll(out, true, true), std::runtime_error);
  EXPECT_EQ(roislam::testing::outputListing(tmp), std::vector<std::string>{"out"});
  for (const auto& f : before)
    EXPECT_EQ(readFile(fs::path(out) / f), contents[f]) << f;
  EXPECT_EQ(readFile(fs::path(out) / "snapshot.png"), "an earlier snapshot");
  // And the same run without the failure replaces it whole.
  writeAll(out, true, false);
  EXPECT_EQ(roislam::testing::outputListing(out), before);
  fs::remove_all(tmp);
}
