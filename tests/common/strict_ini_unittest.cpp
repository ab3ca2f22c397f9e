/* CStrictIniFile: every malformed line of an ini is an error naming file and
 * line, before MRPT's tolerant parser sees it; valid files read as MRPT reads
 * them (shipped configs included). */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using roislam::common::CStrictIniFile;

namespace
{
/** The error of checking `text` as "t.ini", or "" when it is accepted. */
std::string errorOf(const std::string& text)
{
  try
  {
    CStrictIniFile::check(text, "t.ini");
  }
  catch (const std::runtime_error& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(StrictIni, MalformedSectionHeaderNamesFileAndLine)
{
  // The issue's example: MRPT accepts this file and runs on the defaults.
  EXPECT_EQ(errorOf("[this is not"), "t.ini:1: malformed section header '[this is not'");
  EXPECT_EQ(errorOf("# c\n[]\n"), "t.ini:2: malformed section header '[]'");
  EXPECT_EQ(errorOf("[A] b\n"), "t.ini:1: malformed section header '[A] b'");
  EXPECT_EQ(errorOf("[A[B]]\n"), "t.ini:1: malformed section header '[A[B]]'");
  EXPECT_EQ(errorOf("[A]  ; comment\nk = 1\n"), "");
}

TEST(StrictIni, GarbageLineNamesFileAndLine)
{
  EXPECT_EQ(
      errorOf("[A]\nk = 1\nthis is garbage\n"),
      "t.ini:3: expected a comment, [section] or key = value, got 'this is garbage'");
  EXPECT_EQ(
      errorOf("[A]\n= 5\n"), "t.ini:2: expected a comment, [section] or key = value, got '= 5'");
  EXPECT_EQ(
      errorOf("[A]\nmy key = 5\n"),
      "t.ini:2: expected a comment, [section] or key = value, got 'my key = 5'");
  EXPECT_NE(
      errorOf(std::string("[A]\nk = 1\0x\n", 12)).find("t.ini:2: NUL byte"), std::string::npos);
  EXPECT_EQ(
      errorOf("[A]\n@define\n"), "t.ini:2: malformed @define (expected '@define NAME value')");
}

TEST(StrictIni, DuplicateKeyNamesBothLines)
{
  EXPECT_EQ(errorOf("[A]\nk = 1\n\nk = 2\n"), "t.ini:4: duplicate key 'k' (first given on line 2)");
  // MRPT looks keys and sections up case-insensitively, and merges repeated sections.
  EXPECT_EQ(
      errorOf("[A]\nKey = 1\n[B]\nkey = 1\n[a]\nkEY = 2\n"),
      "t.ini:6: duplicate key 'kEY' (first given on line 2)");
}

TEST(StrictIni, KeyOutsideAnySection)
{
  EXPECT_EQ(errorOf("# header\nk = 1\n[A]\n"), "t.ini:2: key 'k' outside any [section]");
}

TEST(StrictIni, ValidSyntaxReadsAsMrptReadsIt)
{
  const std::string text =
      "; MRPT-style comment\n"
      "# hash comment\n"
      "// slash comment\n"
      "@define SIZE 4\n"
      "\n"
      "[Sec]\r\n"
      "  a = 1\n"
      "b=two words\n"
      "empty =\n"
      "list = 1 2 \\\n"
      "  3 4\n"
      "url = http://example.org/x\n"
      "c = ${SIZE}\n"
      "d = 7 // trailing comment\n";
  EXPECT_EQ(errorOf(text), "");
  const auto cfg = CStrictIniFile::fromText(text, "t.ini");
  EXPECT_EQ(cfg.read_int("Sec", "a", 0), 1);
  EXPECT_EQ(cfg.read_string("Sec", "b", ""), "two words");
  EXPECT_EQ(cfg.read_int("Sec", "c", 0), 4);
  EXPECT_EQ(cfg.read_int("Sec", "d", 0), 7);
  std::vector<int> list;
  cfg.read_vector("Sec", "list", std::vector<int>(), list);
  EXPECT_EQ(list, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(cfg.lineOf("sec", "A"), 7u);
  EXPECT_EQ(cfg.lineOf("Sec", "list"), 10u);
  EXPECT_EQ(cfg.lineOf("Sec", "c"), 13u);
  EXPECT_FALSE(cfg.lineOf("Sec", "zz"));
}

TEST(StrictIni, ShippedConfigsPassAndReadLikeMrptsOwnReader)
{
  const fs::path dir = fs::path(roislam::testing::sourceDir()) / "config";
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir))
  {
    if (e.path().extension() != ".ini")
      continue;
    ++files;
    const std::string file = e.path().string();
    const CStrictIniFile strict(file);
    const mrpt::config::CConfigFile mrpt(file);
    std::vector<std::string> sections, mrptSections;
    strict.getAllSections(sections);
    mrpt.getAllSections(mrptSections);
    EXPECT_EQ(sections, mrptSections) << file;
    for (const auto& s : sections)
    {
      std::vector<std::string> keys;
      strict.getAllKeys(s, keys);
      for (const auto& k : keys)
        EXPECT_EQ(strict.read_string(s, k, "?"), mrpt.read_string(s, k, "!")) << file << " " << k;
    }
  }
  EXPECT_GE(files, 4);
}

TEST(StrictIni, MissingFileAndFolderAreNamed)
{
  try
  {
    CStrictIniFile f("/nonexistent/x.ini");
    FAIL() << "accepted a missing file";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_STREQ(e.what(), "ini /nonexistent/x.ini: cannot open");
  }
  const std::string dir = roislam::testing::makeTempDir("strict_ini");
  EXPECT_THROW(CStrictIniFile f(dir), std::runtime_error);
  std::ofstream(dir + "/bad.ini") << "[A]\nk = 1\nk = 2\n";
  try
  {
    CStrictIniFile f(dir + "/bad.ini");
    FAIL() << "accepted a duplicate key";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_EQ(std::string(e.what()), dir + "/bad.ini:3: duplicate key 'k' (first given on line 2)");
  }
  fs::remove_all(dir);
}

TEST(StrictIni, UnknownVariableNamesFileAndLine)
{
  // Found by fuzz_ini: MRPT's own message ("Line 20: Unknown variable") named no file.
  EXPECT_EQ(errorOf("[A]\nk = ${N}\n"), "t.ini:2: unknown variable ${N} (no @define above)");
  EXPECT_EQ(errorOf("[A]\nk = ${N\n"), "t.ini:2: unterminated '${'");
  EXPECT_EQ(errorOf("@define N 3\n[A]\nk = ${N}\n"), "");
  // Whatever MRPT's preprocessing still rejects is named with the file.
  try
  {
    CStrictIniFile::fromText("[A]\nk = $eval{1+}\n", "t.ini");
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind("t.ini: ", 0), 0u) << e.what();
  }
}
