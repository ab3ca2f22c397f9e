/* feature-bench end to end on the shared TUM sequence: SURF against SIFT at the
 * same cap (speed) and the JSON output; bad arguments give a one-line error. */
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace
{
std::string app()
{
  return roislam::testing::binaryDir() + "/apps/feature-bench/feature-bench";
}

/** Runs a shell command; returns (exit code, stdout). */
std::pair<int, std::string> runCmd(const std::string& cmd)
{
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p)
    return {-1, out};
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0)
    out.append(buf.data(), n);
  const int status = pclose(p);
  return {WEXITSTATUS(status), out};
}
}  // namespace

TEST(FeatureBenchApp, BadInputGivesOneLineErrorAndExitCode1)
{
  const auto [code, out] = runCmd(app() + " --input /nonexistent/dir 2>&1");
  EXPECT_EQ(code, 1);
  EXPECT_NE(out.find("feature-bench: error: "), std::string::npos) << out;
  EXPECT_NE(out.find("/nonexistent/dir/rgb.txt"), std::string::npos) << out;
}

TEST(FeatureBenchApp, SurfIsFasterThanSiftOnSharedFrames)
{
  ROISLAM_REQUIRE_SHARED_TUM(dir);
  const auto [code, out] = runCmd(
      app() + " --input " + dir +
      " --frames 3 --extractors sift,surf --transforms rot30,scale1.5 --json 2>/dev/null");
  ASSERT_EQ(code, 0) << out;
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j["frames"], 3);
  EXPECT_EQ(j["max_features"], 1000);
  double msSift = 0, msSurf = 0;
  for (const auto& r : j["results"])
  {
    EXPECT_GE(r["repeatability"].get<double>(), 0.0);
    EXPECT_LE(r["repeatability"].get<double>(), 1.0);
    if (r["transform"] == "none")
    {
      (r["extractor"] == "sift" ? msSift : msSurf) = r["ms_per_frame"].get<double>();
      EXPECT_GT(r["keypoints_per_frame"].get<double>(), 100);
    }
    else
      EXPECT_GT(r["repeatability"].get<double>(), 0.3) << r.dump();
  }
  ASSERT_GT(msSurf, 0);
  // Measured 4-5x on a quiet machine; 1.5x leaves room for a loaded one.
  EXPECT_GT(msSift / msSurf, 1.5) << "SIFT " << msSift << " ms, SURF " << msSurf << " ms";
}
