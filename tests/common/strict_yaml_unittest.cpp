/* checkStrictYaml: the calibration-file YAML subset, checked line by line
 * before MRPT's reader (which keeps the last of two equal keys and reports
 * syntax errors as missing keys). */
#include <gtest/gtest.h>
#include <mrpt/containers/yaml.h>
#include <mrpt/img/TCamera.h>
#include <roislam/common/StrictYaml.h>

#include <sstream>
#include <string>

using roislam::common::checkStrictYaml;

namespace
{
std::string errorOf(const std::string& text)
{
  try
  {
    checkStrictYaml(text, "c.yaml");
  }
  catch (const std::runtime_error& e)
  {
    return e.what();
  }
  return "";
}

std::string cameraYaml()
{
  mrpt::img::TCamera c;
  c.ncols = 640;
  c.nrows = 480;
  c.setIntrinsicParamsFromValues(517.3, 516.5, 318.6, 255.3);
  c.distortion = mrpt::img::DistortionModel::plumb_bob;
  c.dist[0] = 0.26;
  c.cameraName = "fr1";
  std::ostringstream out;
  c.asYAML().printAsYAML(out);
  return out.str();
}
}  // namespace

TEST(StrictYaml, AcceptsWhatMrptWritesAndRosLayouts)
{
  EXPECT_EQ(errorOf(cameraYaml()), "");
  EXPECT_EQ(
      errorOf("# ROS camera_info\n"
              "image_width: 640\n"
              "camera_name: \"my cam\"   # comment\n"
              "camera_matrix:\n"
              "  rows: 3\n"
              "  data: [517.3, 0, 318.6,\n"
              "         0, 516.5, 255.3,\n"
              "         0, 0, 1]\n"
              "distortion_model: plumb_bob\n"
              "tagged: !!opencv-matrix\n"
              "  rows: 1\n"
              "url: http://x/y#frag\n"
              "...\n"),
      "");
}

TEST(StrictYaml, DuplicateKeysAtAnyLevel)
{
  EXPECT_EQ(
      errorOf("image_width: 640\nimage_height: 480\nimage_width: 320\n"),
      "c.yaml:3: duplicate key 'image_width' (first given on line 1)");
  EXPECT_EQ(
      errorOf("m:\n  rows: 3\n  cols: 3\n  rows: 4\nn:\n  rows: 1\n"),
      "c.yaml:4: duplicate key 'rows' (first given on line 2)");
}

TEST(StrictYaml, GarbageAndBrokenStructureNameTheLine)
{
  EXPECT_EQ(
      errorOf("image_width: 640\nthis is garbage\n"),
      "c.yaml:2: expected 'key: value', got 'this is garbage'");
  EXPECT_EQ(errorOf("a: 1\n[oops\n"), "c.yaml:2: expected 'key: value', got '[oops'");
  EXPECT_EQ(errorOf("image_width: [\n"), "c.yaml:1: '[' never closed");
  EXPECT_EQ(errorOf("a: [1, 2]]\n"), "c.yaml:1: text after the closing ']': '[1, 2]]'");
  EXPECT_EQ(errorOf("a: [1,\n 2]]\n"), "c.yaml:2: text after the closing ']': ' 2]]'");
  EXPECT_EQ(errorOf("a: ]\n"), "c.yaml:1: unsupported value ']'");
  EXPECT_EQ(errorOf("a: [1, 2] 3\n"), "c.yaml:1: text after the closing ']': '[1, 2] 3'");
  EXPECT_EQ(errorOf("a:\n  b: 1\n c: 2\n"), "c.yaml:3: bad indentation (column 2, expected 1)");
  EXPECT_EQ(errorOf("a: 1\n\tb: 2\n"), "c.yaml:2: tab in indentation (YAML indents with spaces)");
  EXPECT_EQ(errorOf("a: b: c\n"), "c.yaml:1: unexpected ':' in value 'b: c'");
  EXPECT_EQ(errorOf("a: \"open\n"), "c.yaml:1: unterminated quoted value '\"open'");
  EXPECT_EQ(errorOf("a: {x: 1}\n"), "c.yaml:1: flow mappings are not supported");
  EXPECT_EQ(errorOf("a:\n  - 1\n"), "c.yaml:2: expected 'key: value', got '- 1'");
  EXPECT_EQ(errorOf("%YAML:1.0\na: 1\n"), "c.yaml:1: unsupported directive '%YAML:1.0'");
  EXPECT_EQ(
      errorOf("a: 1\n...\nb: 2\n"), "c.yaml:3: content after the end of the document ('...')");
  EXPECT_EQ(errorOf("# only a comment\n"), "c.yaml: no YAML content");
}

TEST(StrictYaml, TruncatedCalibrationIsCaught)
{
  const std::string full = cameraYaml();
  // Cut inside the camera matrix's data: the open sequence is named.
  const auto cut = full.find("data: [") + 10;
  const std::string e = errorOf(full.substr(0, cut));
  EXPECT_NE(e.find("'[' never closed"), std::string::npos) << e;
}

TEST(StrictYaml, SequenceLeftOpenIntoTheNextKeys)
{
  // Found by fuzz_camera: libfyaml printed "wrongly indented flow sequence"
  // on stderr (and leaked its parser) for this shape.
  EXPECT_EQ(
      errorOf("d:\n  data: [0.26oeff:\n  cols: 8\n"),
      "c.yaml:2: ':' inside a sequence (a ']' missing?)");
  EXPECT_EQ(
      errorOf("d:\n  data: [0.26\n  cols 8]\n"),
      "c.yaml:3: sequence continued without indentation (a ']' missing?)");
  EXPECT_EQ(errorOf("d: [1, [2]]\n"), "c.yaml:1: nested sequences are not supported");
  EXPECT_EQ(errorOf("d:\n  data: [1,\n     2]\n"), "");
}

TEST(StrictYaml, KeyWithoutValue)
{
  // Found by fuzz_camera: a null camera_matrix made libfyaml leak its parser.
  EXPECT_EQ(
      errorOf("%YAML 1.2\n---\ncamera_matrix:\n  "), "c.yaml:3: key 'camera_matrix' has no value");
  EXPECT_EQ(errorOf("a:\nb: 1\n"), "c.yaml:1: key 'a' has no value");
}

TEST(StrictYaml, ControlCharactersAndBrokenUtf8)
{
  // Found by fuzz_camera: libfyaml rejects invalid UTF-8 (printing on stderr).
  EXPECT_EQ(
      errorOf("image_height: 48\xff\xff\x0c"
              "0\n"),
      "c.yaml:1: control character or invalid UTF-8");
  EXPECT_EQ(errorOf("a: \x01\n"), "c.yaml:1: control character or invalid UTF-8");
  EXPECT_EQ(errorOf("camera_name: Kamera \xc3\xbc\n"), "");  // UTF-8 is fine
}
