#include "roislam/io/CFrameSource.h"

#include <roislam/io/CRawlogFrameSource.h>
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraPresets.h>

#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::io
{
void CFrameSource::seek(std::size_t index)
{
  if (index >= size())
    throw std::out_of_range(name() + ": no frame " + std::to_string(index));
  rewind();
  for (std::size_t i = 0; i < index; ++i)
    next();
}

std::unique_ptr<CFrameSource> CFrameSource::open(
    const std::string& path, const std::string& cameraSpec)
{
  if (fs::is_directory(path))
    return std::make_unique<CTumFrameSource>(path, resolveCamera(cameraSpec, path));
  if (!fs::exists(path))
    throw std::runtime_error(path + ": no such file or folder");
  std::optional<mrpt::img::TCamera> override;
  if (cameraSpec != "auto")
    override = resolveCamera(cameraSpec, fs::absolute(path).parent_path().string());
  return std::make_unique<CRawlogFrameSource>(path, CRawlogFrameSource::TOptions(), override);
}
}  // namespace roislam::io
