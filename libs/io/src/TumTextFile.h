/* What the TUM benchmark's text files share (trajectories, accelerometer
 * logs): rows of numbers with '#' comments, shortest exact number text, and
 * writing through a temporary file. Private to libs/io.
 */
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace roislam::io::tumtext
{
/** The rows of numbers of `file`: separators spaces, commas or tabs (as the
 *  benchmark scripts); '#' comments and blank lines ignored; rows with a NaN
 *  skipped. Every other row must have exactly `columns` numbers, `what`
 *  names them in the error. Throws std::runtime_error "<file>:<line>: ..."
 *  on a malformed line or an infinite value, "<file>: cannot open" when
 *  unreadable. */
std::vector<std::vector<double>> readRows(
    const std::string& file, std::size_t columns, const std::string& what);

/** One row of numbers as read, with where it was. */
struct TRow
{
  std::vector<double> values;
  std::size_t line = 0;  //!< 1-based line number in the file
  bool hasNan = false;   //!< some value is NaN (readRows() skips such rows)
};

/** As readRows(), but keeps the rows with a NaN (flagged) and each row's line
 *  number, for readers that reject such rows naming the line. */
std::vector<TRow> readRowsWithLines(
    const std::string& file, std::size_t columns, const std::string& what);

/** Shortest fixed-notation text that reads back as exactly the same double. */
std::string formatDouble(double x);

/** "# <line>" for each line of `comment` (nothing when empty). */
std::string commentLines(const std::string& comment);

/** Writes `text` to `file` through a temporary file renamed on success;
 *  throws std::runtime_error "<file>: ..." on failure. */
void writeAtomically(const std::string& file, const std::string& text);
}  // namespace roislam::io::tumtext
