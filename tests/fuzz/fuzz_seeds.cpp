/* Writes the seed corpus of every fuzz target into <out>/<target>/: small
 * inputs like the unit tests', the files of the shared TUM sequences (read
 * where they are, copied only into the build tree), the shipped configs and
 * reference numbers. Run by ctest before the fuzzers and the replays.
 *
 *   fuzz_seeds <out> <source dir> <shared data dir (may be absent)>
 */
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/containers/yaml.h>
#include <mrpt/img/TCamera.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <roislam/bench/CExperimentPlan.h>
#include <roislam/bench/TRunRecord.h>
#include <roislam/io/CRawlogWriter.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/ObservationConversion.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace
{
fs::path gOut;

void seed(const std::string& target, const std::string& name, const std::string& bytes)
{
  fs::create_directories(gOut / target);
  std::ofstream(gOut / target / name, std::ios::binary) << bytes;
}

std::string readFile(const fs::path& p)
{
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

roislam::io::TRGBDFrame frame(int i, int w, int h)
{
  roislam::io::TRGBDFrame f;
  f.index = static_cast<std::size_t>(i);
  f.timestamp = f.depthTimestamp = 1.0 + i / 30.0;
  f.rgb = cv::Mat(h, w, CV_8UC3, cv::Scalar(10 * i, 80, 200));
  f.depth = cv::Mat(h, w, CV_32FC1, cv::Scalar(1.0f + 0.1f * i));
  f.camera = roislam::io::cameraPreset("ros");
  f.camera.ncols = static_cast<uint32_t>(w);
  f.camera.nrows = static_cast<uint32_t>(h);
  return f;
}

void rawlogSeeds()
{
  const fs::path tmp = gOut / "rawlog.tmp";
  fs::create_directories(tmp);
  {
    // Observation-only, uncompressed (a fuzzer mutates plain bytes better).
    roislam::io::CRawlogWriter w((tmp / "obs.rawlog").string(), 0);
    for (int i = 0; i < 3; ++i)
      w.write(*roislam::io::frameToObservation(frame(i, 8, 6)));
    w.commit();
  }
  {
    // Action / sensory-frame layout, as rawlog-grabber writes it.
    roislam::io::CRawlogWriter w((tmp / "sf.rawlog").string(), 0);
    mrpt::obs::CSensoryFrame sf;
    sf.insert(roislam::io::frameToObservation(frame(0, 8, 6)));
    w.write(sf);
    w.commit();
  }
  for (const char* f : {"obs.rawlog", "sf.rawlog"})
    seed("rawlog", f, readFile(tmp / f));
  fs::remove_all(tmp);
}

void cameraSeeds()
{
  for (const char* preset : {"fr1", "fr3"})
  {
    const auto cam = roislam::io::cameraPreset(preset);
    mrpt::config::CConfigFileMemory ini;
    cam.saveToConfigFile("CAMERA_PARAMS", ini);
    seed("camera", std::string(preset) + ".ini", std::string(1, '\0') + ini.getContent());
    std::ostringstream yaml;
    cam.asYAML().printAsYAML(yaml);
    seed("camera", std::string(preset) + ".yaml", std::string(1, '\1') + yaml.str());
  }
  // MRPT's older layout: dist without distortion_model.
  seed(
      "camera", "old.ini",
      std::string(1, '\0') +
          "[CAMERA_PARAMS]\nresolution = [640 480]\ncx = 318.6\ncy = 255.3\nfx = 517.3\n"
          "fy = 516.5\ndist = [0.26 -0.95 -0.005 0.002 1.16]\n");
}

void benchSeeds(const fs::path& src)
{
  mrpt::config::CConfigFileMemory plan;
  roislam::bench::CExperimentPlan::TOptions().saveToConfigFile(plan, "Bench");
  seed("bench_files", "plan.ini", std::string(1, '\0') + plan.getContent());
  roislam::bench::TRunRecord rec;
  rec.run.id = "t2-seq-roi_big-orb-600-fallback";
  rec.run.test = 2;
  rec.run.app = "roi-graphslam";
  rec.run.argv = {"roi-graphslam", "--input", "seq"};
  rec.ok = true;
  rec.summary = {{"frames", 90}, {"ate_rmse", 0.01}, {"failed", false}};
  seed("bench_files", "run.json", std::string(1, '\1') + rec.toJson().dump(2));
  seed(
      "bench_files", "dissertation.json",
      std::string(1, '\2') + readFile(src / "share/roi-bench/dissertation.json"));
  seed("bench_files", "variant", std::string(1, '\3') + "strict:FrontEnd.strict_roi=true");
}

void textSeeds(const fs::path& src, const fs::path& shared)
{
  seed("tum_list", "small.txt", "# color images\n1.0 rgb/1.png\n2.0,rgb/2.png\n3.0\trgb.txt\n");
  seed(
      "trajectory", "small.txt",
      "# gt\n1.0 1 2 3 0 0 0 1\n2.0,4,5,6,0,0,1,1\n3.0 nan 0 0 0 0 0 1\n");
  seed(
      "seven_scenes_pose", "rigid.txt",
      "0.19298998693231886\t-0.3781226715774525\t0.90541598736878581\t0.11401524362797334\t\n"
      "-0.97920237757954853\t-0.01535778391951924\t0.20230383638389191\t-0.1149161556437033\t\n"
      "-0.062590483992557081\t-0.92562810227013492\t-0.37322251754330971\t1.4117711745589332\t\n"
      "0\t0\t0\t1\t\n");
  seed(
      "seven_scenes_pose", "lost.txt",
      "-inf -inf -inf -inf\n-inf -inf -inf -inf\n"
      "-inf -inf -inf -inf\n0 0 0 1\n");
  seed("seven_scenes_pose", "short.txt", "1 0 0 0\n0 1 0 0\n0 0 1 0\n");
  for (const auto& e : fs::directory_iterator(src / "tests/evaluation/data"))
    seed("trajectory", e.path().filename().string(), readFile(e.path()));
  for (const auto& e : fs::directory_iterator(src / "config"))
    if (e.path().extension() == ".ini")
      seed("ini", e.path().filename().string(), readFile(e.path()));
  // A graph as roi-graphslam writes it, and one with everything the reader
  // accepts (comments, blank lines, two edges between the same nodes).
  seed(
      "graph", "small.graph",
      "VERTEX3 0 0 0 0 0 -0 0\nFIX 0\nVERTEX3 1 0.10000000000000001 0 0 0 0 "
      "0.050000000000000003\nEDGE3 0 1 0.10000000000000001 0 0 0 0 0.050000000000000003 "
      "10000 1 2 3 4 5 10000 6 7 8 9 10000 10 11 12 400 13 14 400 15 400\n");
  seed(
      "graph", "comments.graph",
      "# graph\n\nVERTEX3 2 1 2 3 0.1 0.2 0.3\nVERTEX3 5 -1 0 1e-3 3.1 -1.5 -3.1\nFIX 5\n"
      "EDGE3 2 5 1 1 1 0 0 0 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n"
      "EDGE3 2 5 1 1 1 0 0 0 4 0 0 0 0 0 4 0 0 0 0 4 0 0 0 4 0 0 4 0 4\n");
  seed("ini", "mrpt.ini", "; c\n@define N 4\n[A]\nk = ${N} // c\nv = 1 2 \\\n 3\n[B]\nx=\n");
  if (!fs::is_directory(shared / "tum"))
    return;
  for (const auto& seq : fs::directory_iterator(shared / "tum"))
  {
    const std::string name = seq.path().filename().string();
    for (const char* f : {"rgb.txt", "depth.txt"})
      if (fs::exists(seq.path() / f))
        seed("tum_list", name + "_" + f, readFile(seq.path() / f));
    if (fs::exists(seq.path() / "groundtruth.txt"))
      seed("trajectory", name + "_groundtruth.txt", readFile(seq.path() / "groundtruth.txt"));
  }
}
}  // namespace

int main(int argc, char** argv)
{
  if (argc != 4)
  {
    std::cerr << "usage: fuzz_seeds <out> <source dir> <shared data dir>\n";
    return 2;
  }
  try
  {
    gOut = argv[1];
    fs::remove_all(gOut);
    textSeeds(argv[2], argv[3]);
    cameraSeeds();
    rawlogSeeds();
    benchSeeds(argv[2]);
  }
  catch (const std::exception& e)
  {
    std::cerr << "fuzz_seeds: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
