#include "roislam/common/TextFiles.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace fs = std::filesystem;

namespace roislam::common
{
void writeFileAtomically(const std::string& file, const std::string& content)
{
  const std::string tmp = file + ".tmp" + std::to_string(getpid()) + "_" +
                          std::to_string(std::hash<std::thread::id>()(std::this_thread::get_id()));
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out)
      throw std::runtime_error(file + ": cannot write");
    out << content;
    out.flush();
    if (!out)
      throw std::runtime_error(file + ": write failed");
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec)
  {
    fs::remove(tmp, ec);
    throw std::runtime_error(file + ": cannot rename temporary file into place");
  }
}

std::string readFile(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw std::runtime_error(file + ": cannot open");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace roislam::common
