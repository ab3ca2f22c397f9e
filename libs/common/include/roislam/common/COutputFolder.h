/* An app's output folder, complete or absent: the files are written into a
 * hidden staging folder beside the target (".<name>.partial-<pid>") that
 * commit() renames into place once everything is written. Until then the
 * target is untouched; an exception (any failure while writing) destroys the
 * object uncommitted, which deletes the staging folder, so after a failure the
 * target is absent or exactly as before. Only a process killed outright
 * (SIGKILL, power loss) can leave a staging folder behind, never a half-new
 * target.
 *
 * A target that exists must be an empty folder, unless `overwrite`: then it
 * may hold only the entries the app itself writes (`known`, e.g.
 * "trajectory.txt", "landmarks") or that an earlier commit listed in the
 * folder's manifest (kManifest, written by commit(): one entry per line, so
 * an optional output of an earlier run, such as roi-landmarks' annotated
 * rawlog, is recognised as ours), and commit() swaps it for the new folder
 * and deletes the old one, so files of an earlier run (an old snapshot.png
 * after --no-snapshot) never mix with new ones. A folder holding anything
 * else is never replaced. Used by every app that writes a folder
 * (roi-graphslam through CSlamOutputWriter, roi-landmarks, roi-bench's run
 * folders, rgbd-simul).
 */
#pragma once

#include <string>
#include <vector>

namespace roislam::common
{
class COutputFolder
{
 public:
  struct TOptions
  {
    /** Replace an earlier output (see the header comment). */
    bool overwrite = false;
    /** File and folder names (first level) the app writes. */
    std::vector<std::string> known;
    /** Also accepted in an earlier output: names starting with one of these. */
    std::vector<std::string> knownPrefixes;
    /** Everything in the target is ours (a sub-folder of our own output, such
     *  as roi-bench's charts/): overwrite replaces it whatever it holds. */
    bool ownsEverything = false;
  };

  /** Checks the target and creates the staging folder. Throws
   *  std::runtime_error "output dir <target>: ..." when the target is not a
   *  folder, is not empty (and not replaceable), or cannot be written. */
  COutputFolder(const std::string& target, const TOptions& options);
  /** Deletes the staging folder unless committed. */
  ~COutputFolder();
  COutputFolder(const COutputFolder&) = delete;
  COutputFolder& operator=(const COutputFolder&) = delete;

  /** Where to write now: the staging folder (no trailing '/'). */
  const std::string& path() const { return m_staging; }
  /** Where the files end up. */
  const std::string& target() const { return m_target; }

  /** Moves the staging folder into place (replacing the earlier output when
   *  allowed). Throws "output dir <target>: ..." on failure, leaving the
   *  target as before. Afterwards path() is the target. */
  void commit();
  bool committed() const { return m_committed; }

  /** Throws unless `dir` is absent, an empty folder, or (overwrite) a folder
   *  holding only known entries; names the first foreign entry. */
  static void checkReplaceable(const std::string& dir, const TOptions& options);

  /** The manifest commit() writes into the folder. */
  static constexpr const char* kManifest = ".roislam-output";

 private:
  void writeManifest() const;
  std::string m_given;  //!< the target as given, for messages
  std::string m_target, m_staging;
  TOptions m_options;
  bool m_committed = false;
};
}  // namespace roislam::common
