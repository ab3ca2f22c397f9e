/* Writes an MRPT rawlog (observation-only format, gz-compressed) atomically:
 * objects go to a temporary file next to the target, which commit() renames
 * to the final name; if the writer is destroyed without commit() (an error
 * somewhere) the temporary file is removed, so no partial rawlog is left.
 * Used by tum2rawlog and the simulator.
 */
#pragma once

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/serialization/CSerializable.h>

#include <memory>
#include <string>

namespace roislam::io
{
class CRawlogWriter
{
 public:
  /** Creates the temporary file. compressLevel: 0 (none) .. 9 (best).
   *  Throws std::runtime_error "<file>: cannot write ..." when the folder is
   *  missing or not writable. */
  explicit CRawlogWriter(const std::string& file, int compressLevel = 1);
  ~CRawlogWriter();
  CRawlogWriter(const CRawlogWriter&) = delete;
  CRawlogWriter& operator=(const CRawlogWriter&) = delete;

  /** Appends one object (e.g. an observation). */
  void write(const mrpt::serialization::CSerializable& obj);
  /** Closes the file and renames it to the final name (replacing an old one). */
  void commit();

  std::size_t count() const { return m_count; }
  /** Final path (absolute). */
  const std::string& file() const { return m_file; }

 private:
  std::string m_file;
  std::string m_temp;
  std::unique_ptr<mrpt::io::CFileGZOutputStream> m_out;
  std::size_t m_count = 0;
  bool m_committed = false;
};
}  // namespace roislam::io
