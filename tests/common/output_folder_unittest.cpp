/* COutputFolder: a folder is complete (committed) or absent / untouched after
 * a failure; non-empty folders are refused unless overwrite, and then only
 * when they hold nothing but the app's own files. */
#include <gtest/gtest.h>
#include <roislam/common/COutputFolder.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;
using roislam::common::COutputFolder;

namespace
{
std::string readFile(const fs::path& p)
{
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeFile(const fs::path& p, const std::string& text)
{
  std::ofstream(p) << text;
}

std::size_t entries(const fs::path& dir)
{
  return static_cast<std::size_t>(
      std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

COutputFolder::TOptions known(bool overwrite)
{
  COutputFolder::TOptions o;
  o.overwrite = overwrite;
  o.known = {"a.txt", "b.txt", "sub"};
  o.knownPrefixes = {"frame_"};
  return o;
}

std::string errorOf(const std::string& target, const COutputFolder::TOptions& o)
{
  try
  {
    COutputFolder f(target, o);
  }
  catch (const std::runtime_error& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(OutputFolder, CommitMovesTheFilesIntoPlace)
{
  const fs::path dir = roislam::testing::makeTempDir("outfolder_commit");
  const fs::path target = dir / "out";
  {
    COutputFolder f(target.string(), known(false));
    EXPECT_NE(f.path(), target.string());
    EXPECT_EQ(fs::path(f.path()).parent_path(), dir);
    writeFile(fs::path(f.path()) / "a.txt", "new");
    EXPECT_FALSE(fs::exists(target));
    f.commit();
    EXPECT_EQ(f.path(), target.string());
  }
  EXPECT_EQ(readFile(target / "a.txt"), "new");
  EXPECT_EQ(entries(dir), 1u);  // no staging folder left
  // An existing empty folder is an absent output.
  fs::create_directories(dir / "empty");
  {
    COutputFolder f((dir / "empty").string(), known(false));
    writeFile(fs::path(f.path()) / "b.txt", "b");
    f.commit();
  }
  EXPECT_EQ(readFile(dir / "empty" / "b.txt"), "b");
  fs::remove_all(dir);
}

TEST(OutputFolder, FailureWhileWritingLeavesNoFolder)
{
  const fs::path dir = roislam::testing::makeTempDir("outfolder_fail");
  const fs::path target = dir / "out";
  try
  {
    COutputFolder f(target.string(), known(false));
    writeFile(fs::path(f.path()) / "a.txt", "half");
    throw std::runtime_error("injected failure");
  }
  catch (const std::runtime_error&)
  {
  }
  EXPECT_FALSE(fs::exists(target));
  EXPECT_EQ(entries(dir), 0u);
  fs::remove_all(dir);
}

TEST(OutputFolder, NonEmptyFolderRefusedUnlessOverwrite)
{
  const fs::path dir = roislam::testing::makeTempDir("outfolder_nonempty");
  const fs::path target = dir / "out";
  fs::create_directories(target / "sub");
  writeFile(target / "a.txt", "old a");
  writeFile(target / "b.txt", "old b");  // stale: the new run does not write it
  writeFile(target / "frame_7.png", "old frame");
  EXPECT_EQ(
      errorOf(target.string(), known(false)),
      "output dir " + target.string() +
          ": not empty (holds a.txt); use --overwrite to replace an earlier output");

  // Overwrite: the earlier output stays untouched until commit, and a failure
  // before commit keeps it.
  try
  {
    COutputFolder f(target.string(), known(true));
    writeFile(fs::path(f.path()) / "a.txt", "half");
    throw std::runtime_error("injected failure");
  }
  catch (const std::runtime_error&)
  {
  }
  EXPECT_EQ(readFile(target / "a.txt"), "old a");
  EXPECT_EQ(readFile(target / "b.txt"), "old b");
  EXPECT_EQ(entries(dir), 1u);

  // Commit replaces the whole folder: the stale files are gone.
  {
    COutputFolder f(target.string(), known(true));
    writeFile(fs::path(f.path()) / "a.txt", "new a");
    f.commit();
  }
  EXPECT_EQ(readFile(target / "a.txt"), "new a");
  EXPECT_FALSE(fs::exists(target / "b.txt"));
  EXPECT_FALSE(fs::exists(target / "frame_7.png"));
  EXPECT_FALSE(fs::exists(target / "sub"));
  EXPECT_EQ(entries(dir), 1u);
  fs::remove_all(dir);
}

TEST(OutputFolder, ManifestNamesWhatAnEarlierRunWrote)
{
  const fs::path dir = roislam::testing::makeTempDir("outfolder_manifest");
  const fs::path target = dir / "out";
  {
    // An earlier run wrote an optional entry this run does not know.
    auto o = known(false);
    o.known.push_back("annotated.rawlog");
    COutputFolder f(target.string(), o);
    writeFile(fs::path(f.path()) / "annotated.rawlog", "old");
    writeFile(fs::path(f.path()) / "a.txt", "old a");
    f.commit();
  }
  const std::string manifest = readFile(target / COutputFolder::kManifest);
  EXPECT_EQ(manifest.substr(manifest.find("\na.txt") + 1), "a.txt\nannotated.rawlog\n");
  {
    COutputFolder f(target.string(), known(true));
    writeFile(fs::path(f.path()) / "a.txt", "new a");
    f.commit();
  }
  EXPECT_FALSE(fs::exists(target / "annotated.rawlog"));
  EXPECT_EQ(readFile(target / "a.txt"), "new a");
  fs::remove_all(dir);
}

TEST(OutputFolder, ForeignFilesAreNeverReplaced)
{
  const fs::path dir = roislam::testing::makeTempDir("outfolder_foreign");
  const fs::path target = dir / "out";
  fs::create_directories(target);
  writeFile(target / "a.txt", "old a");
  writeFile(target / "notes.txt", "precious");
  EXPECT_EQ(
      errorOf(target.string(), known(true)),
      "output dir " + target.string() +
          ": holds notes.txt, which this app does not write; not replaced (choose another "
          "folder)");
  // A foreign file appearing while the app runs is caught at commit.
  fs::remove(target / "notes.txt");
  {
    COutputFolder f(target.string(), known(true));
    writeFile(target / "late.txt", "precious");
    EXPECT_THROW(f.commit(), std::runtime_error);
  }
  EXPECT_EQ(readFile(target / "late.txt"), "precious");
  EXPECT_EQ(readFile(target / "a.txt"), "old a");
  EXPECT_EQ(entries(dir), 1u);
  fs::remove_all(dir);
}

TEST(OutputFolder, UnwritableOrNotAFolderIsNamed)
{
  const fs::path dir = roislam::testing::makeTempDir("outfolder_bad");
  writeFile(dir / "file", "x");
  // Below a regular file (fails for root too, unlike permissions).
  const std::string below = (dir / "file" / "out").string();
  const std::string e1 = errorOf(below, known(false));
  EXPECT_EQ(e1.rfind("output dir " + below + ": cannot create", 0), 0u) << e1;
  const std::string e2 = errorOf((dir / "file").string(), known(true));
  EXPECT_EQ(e2, "output dir " + (dir / "file").string() + ": exists and is not a folder");
  EXPECT_EQ(errorOf("", known(false)), "output dir: no folder given");
  EXPECT_EQ(entries(dir), 1u);
  fs::remove_all(dir);
}
