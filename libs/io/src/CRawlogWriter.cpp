#include "roislam/io/CRawlogWriter.h"

#include <mrpt/serialization/CArchive.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::io
{
CRawlogWriter::CRawlogWriter(const std::string& file, int compressLevel)
{
  if (file.empty())
    throw std::invalid_argument("CRawlogWriter: empty output file name");
  m_file = fs::absolute(file).lexically_normal().string();
  if (fs::is_directory(m_file))
    throw std::runtime_error(m_file + ": cannot write (is a folder)");
  // mkstemp gives a unique name in the target folder so the final rename is atomic.
  std::string tmpl = m_file + ".partial-XXXXXX";
  const int fd = mkstemp(tmpl.data());
  if (fd < 0)
    throw std::runtime_error(m_file + ": cannot write (" + std::strerror(errno) + ")");
  ::close(fd);
  m_temp = tmpl;
  m_out = std::make_unique<mrpt::io::CFileGZOutputStream>();
  if (!m_out->open(m_temp, std::max(0, std::min(9, compressLevel))))
  {
    fs::remove(m_temp);
    throw std::runtime_error(m_file + ": cannot write (gz open failed)");
  }
}

CRawlogWriter::~CRawlogWriter()
{
  if (m_committed)
    return;
  m_out.reset();
  std::error_code ec;
  fs::remove(m_temp, ec);
}

void CRawlogWriter::write(const mrpt::serialization::CSerializable& obj)
{
  if (m_committed)
    throw std::logic_error("CRawlogWriter::write after commit");
  try
  {
    auto arch = mrpt::serialization::archiveFrom(*m_out);
    arch << obj;
  }
  catch (const std::exception&)
  {
    throw std::runtime_error(m_file + ": write error (disk full?)");
  }
  ++m_count;
}

void CRawlogWriter::commit()
{
  if (m_committed)
    return;
  m_out->close();
  m_out.reset();
  std::error_code ec;
  // mkstemp created the file as 0600; give it the usual permissions.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  fs::permissions(m_temp, static_cast<fs::perms>(0666 & ~mask), ec);
  fs::rename(m_temp, m_file, ec);
  if (ec)
    throw std::runtime_error(m_file + ": cannot rename temporary file (" + ec.message() + ")");
  m_committed = true;
}
}  // namespace roislam::io
