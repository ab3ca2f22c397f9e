#include "TumTextFile.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace roislam::io::tumtext
{
namespace
{
/** Parses one number like Python's float() on a stripped token (an optional
 *  leading '+' is allowed; "nan" is accepted and later skips the line). */
bool parseNumber(const std::string& token, double& value)
{
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+')
    ++first;
  if (first == last)
    return false;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && ptr == last;
}
}  // namespace

std::vector<TRow> readRowsWithLines(
    const std::string& file, std::size_t columns, const std::string& what)
{
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw std::runtime_error(file + ": cannot open");

  std::vector<TRow> rows;
  std::string line;
  std::size_t lineNo = 0;
  while (std::getline(in, line))
  {
    ++lineNo;
    // The scripts treat commas and tabs as spaces.
    std::replace(line.begin(), line.end(), ',', ' ');
    std::replace(line.begin(), line.end(), '\t', ' ');
    std::istringstream ss(line);
    std::vector<std::string> tokens;
    for (std::string tok; ss >> tok;)
      tokens.push_back(tok);
    if (tokens.empty() || tokens.front().front() == '#')
      continue;

    const std::string where = file + ":" + std::to_string(lineNo);
    if (tokens.size() != columns)
      throw std::runtime_error(
          where + ": expected " + std::to_string(columns) + " values (" + what + "), found " +
          std::to_string(tokens.size()));
    TRow row;
    row.values.resize(columns);
    row.line = lineNo;
    for (std::size_t k = 0; k < columns; ++k)
    {
      double& v = row.values[k];
      if (!parseNumber(tokens[k], v))
        throw std::runtime_error(where + ": not a number: '" + tokens[k] + "'");
      if (std::isnan(v))
        row.hasNan = true;
      else if (std::isinf(v))
        throw std::runtime_error(where + ": infinite value '" + tokens[k] + "'");
    }
    rows.push_back(std::move(row));
  }
  if (in.bad())
    throw std::runtime_error(file + ": read error");
  return rows;
}

std::vector<std::vector<double>> readRows(
    const std::string& file, std::size_t columns, const std::string& what)
{
  std::vector<std::vector<double>> rows;
  for (auto& r : readRowsWithLines(file, columns, what))
    if (!r.hasNan)
      rows.push_back(std::move(r.values));
  return rows;
}

std::string formatDouble(double x)
{
  std::array<char, 400> buf{};
  // Shortest fixed-notation text that reads back exactly: TUM files never
  // use exponents (a stamp of 1e+09 would look foreign to other tools).
  const auto [ptr, ec] =
      std::to_chars(buf.data(), buf.data() + buf.size(), x, std::chars_format::fixed);
  if (ec != std::errc())
    throw std::runtime_error("cannot format a number");
  return std::string(buf.data(), ptr);
}

std::string commentLines(const std::string& comment)
{
  std::string out;
  std::istringstream hc(comment);
  for (std::string l; std::getline(hc, l);)
    out += "# " + l + "\n";
  return out;
}

void writeAtomically(const std::string& file, const std::string& text)
{
  namespace fs = std::filesystem;
  const std::string tmp = file + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw std::runtime_error(file + ": cannot write");
    out << text;
    out.close();
    if (!out)
    {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw std::runtime_error(file + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec)
  {
    std::error_code ec2;
    fs::remove(tmp, ec2);
    throw std::runtime_error(file + ": cannot write (" + ec.message() + ")");
  }
}
}  // namespace roislam::io::tumtext
