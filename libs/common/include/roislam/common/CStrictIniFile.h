/* An MRPT ini file read strictly: the text is checked line by line before
 * MRPT's own parser sees it, because MRPT 2.5 accepts almost anything (an ini
 * whose only line is "[this is not" loads as an empty file, a garbage line is
 * dropped, a repeated key silently wins). Every app and loader that reads an
 * ini of ours goes through this class; it is a CConfigFileMemory, so the
 * TOptions loaders read it as any MRPT config.
 *
 * Accepted lines (after leading blanks):
 *  - blank lines; comments starting with ';', '#' or "//";
 *  - "[Section]" (a non-empty name without brackets), optionally followed by
 *    a comment;
 *  - "key = value" inside a section: key of letters, digits and "_.-:/",
 *    value possibly empty (MRPT's trailing "// comment" is kept as MRPT reads it);
 *  - MRPT's "@define NAME value" directive;
 *  - a line ending in '\' continues on the next line (MRPT's continuation).
 * Anything else, a key before the first section, or a key given twice in one
 * section (case-insensitively, as MRPT looks keys up; also across repeated
 * "[Section]" headers) throws std::runtime_error "<file>:<line>: <why>".
 */
#pragma once

#include <mrpt/config/CConfigFileMemory.h>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>

namespace roislam::common
{
class CStrictIniFile : public mrpt::config::CConfigFileMemory
{
 public:
  /** Reads and checks `file`. Throws std::runtime_error "ini <file>: cannot
   *  open" when it cannot be read, "<file>:<line>: ..." on a malformed line. */
  explicit CStrictIniFile(const std::string& file);

  /** Checks ini text; `label` names it in errors ("<label>:<line>: ..."). */
  static CStrictIniFile fromText(const std::string& text, const std::string& label);

  /** Throws as the constructor does when `text` is not a valid ini; returns
   *  the line of every key, by (lower-case section, lower-case key). */
  static std::map<std::pair<std::string, std::string>, std::size_t> check(
      const std::string& text, const std::string& label);

  /** Line of a key in the file (1-based), if present. */
  std::optional<std::size_t> lineOf(const std::string& section, const std::string& key) const;

  /** The file name (or label) errors use. */
  const std::string& label() const { return m_label; }

 private:
  CStrictIniFile(const std::string& text, const std::string& label, int /*fromText tag*/);

  std::string m_label;
  std::map<std::pair<std::string, std::string>, std::size_t> m_keyLines;
};
}  // namespace roislam::common
