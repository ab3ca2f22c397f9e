/* What the evaluation's PNG figures share (CTrajectoryPlot, CErrorPlot): a
 * temporary working folder, gnuplot string literals, the terminal set-up and
 * running a script into a PNG written through a temporary name. Private to
 * libs/evaluation.
 */
#pragma once

#include <filesystem>
#include <string>

namespace roislam::evaluation::gnuplot
{
/** A fresh temporary folder, removed with everything in it on every exit path. */
struct TTempDir
{
  std::filesystem::path path;
  TTempDir();
  ~TTempDir();
  TTempDir(const TTempDir&) = delete;
  TTempDir& operator=(const TTempDir&) = delete;
};

/** A gnuplot single-quoted string literal ('' escapes a quote; line breaks
 *  become spaces). */
std::string quoted(const std::string& s);

/** Script lines that select pngcairo (else png) at width x height and set the
 *  output to `image`. */
std::string pngTerminal(int width, int height, const std::filesystem::path& image);

/** Runs `program script` (stdin /dev/null, output to a log in the script's
 *  folder), then copies `image` to `pngFile` through a temporary name.
 *  Throws std::runtime_error naming pngFile when gnuplot is missing, fails or
 *  writes no image, or when pngFile cannot be written. */
void renderPng(
    const std::string& program, const std::filesystem::path& script,
    const std::filesystem::path& image, const std::string& pngFile);
}  // namespace roislam::evaluation::gnuplot
