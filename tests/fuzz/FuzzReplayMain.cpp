/* Runs a fuzz target over files instead of under libFuzzer: every file given,
 * and every file in every folder given. Built with the default compiler into
 * the unit tests, it replays the seed corpus and the regression inputs
 * (crashes the fuzzers once found) on every CI run. */
#include <sys/resource.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv)
{
  namespace fs = std::filesystem;
  // Inputs named oom-*: MRPT's deserialiser allocates whatever size a corrupt
  // rawlog claims (a point count of 3e8 is 3 x 1.3 GB). With the address
  // space limited, the allocation fails with std::bad_alloc and the reader
  // must report a corrupt file. Under ASan / TSan (which reserve terabytes of
  // address space, and report a failed operator new instead of throwing)
  // these inputs are skipped.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  const bool replayOom = false;
#else
  const bool replayOom = true;
  const rlim_t limit = 1ull << 30;
  const rlimit rl{limit, limit};
  setrlimit(RLIMIT_AS, &rl);
#endif
  std::size_t inputs = 0;
  for (int i = 1; i < argc; ++i)
  {
    std::vector<fs::path> files;
    if (fs::is_directory(argv[i]))
    {
      for (const auto& e : fs::recursive_directory_iterator(argv[i]))
        if (e.is_regular_file())
          files.push_back(e.path());
    }
    else if (fs::is_regular_file(argv[i]))
      files.push_back(argv[i]);
    for (const auto& f : files)
    {
      if (!replayOom && f.filename().string().rfind("oom-", 0) == 0)
        continue;
      std::ifstream in(f, std::ios::binary);
      const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
      LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
      ++inputs;
    }
  }
  std::printf("%zu inputs replayed\n", inputs);
  return inputs > 0 ? 0 : 1;
}
