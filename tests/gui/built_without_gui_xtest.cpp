/* roi-graphslam and roi-graphslam-engine built without the live view (ROISLAM_WITH_GUI=OFF, or
 * MRPT without wxWidgets): --gui fails at once with one line saying so,
 * exit code 1, and writes nothing; without --gui the run is unchanged (the
 * other app tests of this build). Added by tests/gui/CMakeLists.txt only
 * in that configuration. */
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

TEST(BuiltWithoutGui, GuiFlagSaysSoInOneLine)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string dir = roislam::testing::makeTempDir("nogui");
  for (const std::string app : {"roi-graphslam", "roi-graphslam-engine"})
    for (const std::string& flag : {std::string("--gui"), "--gui-screenshot " + dir + "/w.png"})
    {
      const std::string exe = roislam::testing::binaryDir() + "/apps/" + app + "/" + app;
      const std::string input =
          app == "roi-graphslam"
              ? " --input " + seq
              : " -i " + roislam::testing::sourceDir() + "/config/graphslam-engine.ini -r " + seq;
      const int rc = std::system((exe + input + " --output-dir " + dir + "/out " + flag +
                                  " > /dev/null 2> " + dir + "/err")
                                     .c_str());
      ASSERT_TRUE(WIFEXITED(rc));
      EXPECT_EQ(WEXITSTATUS(rc), 1) << app << " " << flag;
      std::ifstream f(dir + "/err");
      std::stringstream ss;
      ss << f.rdbuf();
      const std::string err = ss.str();
      EXPECT_EQ(
          err, app + ": error: --gui: " + app +
                   " was built without GUI (MRPT's wxWidgets windows were not found)\n");
      EXPECT_FALSE(fs::exists(dir + "/out")) << flag;
      EXPECT_FALSE(fs::exists(dir + "/w.png")) << flag;
    }
  fs::remove_all(dir);
}
