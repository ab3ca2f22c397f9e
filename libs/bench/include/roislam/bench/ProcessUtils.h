/* Subprocess execution for roi-bench: runs one program with its output sent
 * to files, measures wall time, CPU time and peak memory (wait4 rusage), and
 * enforces an optional time limit. Also shell quoting for the exact command
 * lines written to results.csv and printed by --emit-jobs, and executable
 * lookup. Used by CBenchRunner (app runs) and CChartWriter (gnuplot).
 */
#pragma once

#include <roislam/common/TextFiles.h>

#include <optional>
#include <string>
#include <vector>

namespace roislam::bench
{
struct TProcessResult
{
  bool started = false;   //!< false when the program could not be spawned
  int exitCode = -1;      //!< exit status when it exited normally, else -1
  int signal = 0;         //!< terminating signal, 0 when it exited normally
  bool timedOut = false;  //!< killed because it exceeded the time limit
  double wallS = 0;       //!< s, wall-clock time from spawn to exit
  double cpuS = 0;        //!< s, user + system CPU time of the child
  double maxRssMb = 0;    //!< MiB, peak resident set size of the child
  std::string error;      //!< why it could not be spawned
  bool succeeded() const { return started && !timedOut && signal == 0 && exitCode == 0; }
};

/** Runs argv (argv[0] is a path or a name searched on PATH) with stdin from
 *  /dev/null, stdout and stderr appended to the given files ("" = /dev/null).
 *  timeoutS <= 0 means no limit; on timeout the child gets SIGKILL. Never throws
 *  for a failing child; throws std::invalid_argument on an empty argv. */
TProcessResult runProcess(
    const std::vector<std::string>& argv, const std::string& stdoutFile,
    const std::string& stderrFile, double timeoutS = 0);

/** POSIX shell quoting: the word unchanged when it only has safe characters,
 *  otherwise in single quotes with embedded quotes escaped. */
std::string shellQuote(const std::string& word);
/** argv quoted and joined by spaces: a command line a shell runs verbatim. */
std::string shellJoin(const std::vector<std::string>& argv);

/** The path of an executable file named `name` on PATH, or nullopt. */
std::optional<std::string> findOnPath(const std::string& name);
/** Absolute path of the running executable (/proc/self/exe), or "" when unknown. */
std::string selfExecutablePath();

/** The last `lines` lines of a text file ("" when it does not exist). */
std::string fileTail(const std::string& file, std::size_t lines);
/** Whole text files (roislam/common/TextFiles.h). */
using common::readFile;
using common::writeFileAtomically;
}  // namespace roislam::bench
