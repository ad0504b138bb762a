// A folder of outputs (render's step PNGs and frames.json) replaced as a whole, the folder form of
// TempOutput: the new set is written into a hidden temporary folder beside the old one, and
// commit() swaps the two, so a failed or interrupted run leaves the old set as it was.
#pragma once
#include <functional>
#include <string>

namespace tsp {

/// Which names of an existing output folder belong to the set being replaced.
using BelongsToSet = std::function<bool(const std::string& name)>;

/// A folder replaced as a whole. Entries of an existing folder that belong to the set are
/// dropped with it; every other entry (a user's notes, a movie) must be a regular file or a
/// link, and is carried into the new folder (hard-linked, so never copied or lost). Use from one
/// thread; not copyable.
class OutputFolder {
 public:
  /// Checks dir and prepares `.NAME.tmp-XXXXXX` beside it (a link to a folder: its target is
  /// replaced, the link kept). A dir that does not exist is made empty (so that outputs inside it
  /// have their folder) and removed again, if still empty, unless committed. Throws IoError when dir's parent does not exist, dir exists and is
  /// not a folder, it holds an entry that is not a regular file or link outside the set, or the
  /// temporary folder cannot be made; UsageError when an entry of the set is a guarded input
  /// (InputGuard) or dir holds the current working directory.
  OutputFolder(const std::string& dir, BelongsToSet belongs);
  /// Removes the temporary folder unless committed (the old folder is untouched, a folder this
  /// made is removed when empty).
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  /// The folder to write the new set into.
  const std::string& tmp() const { return tmp_; }
  /// text (an error message) with the temporary folder's path replaced by the folder as given,
  /// so that a failed write names the folder the user asked for. Never throws but bad_alloc.
  std::string as_shown(std::string text) const;
  /// Carries the entries outside the set over, swaps the new folder in (renameat2
  /// RENAME_EXCHANGE, one atomic step) and removes the old set. Throws Interrupted (nothing
  /// replaced) once SIGINT/SIGTERM arrived, IoError when a step fails (the old folder is then
  /// left in place wherever the file system allows).
  void commit();

 private:
  std::string shown_;   ///< dir as given, for messages
  std::string final_;   ///< the folder replaced (a link's target)
  std::string tmp_;     ///< the new set's folder
  BelongsToSet belongs_;
  int lock_fd_ = -1;    ///< locks tmp_'s marker file while this writer lives
  bool created_ = false;  ///< final_ did not exist: made empty, removed again unless committed
  bool committed_ = false;
};

/// Removes the stale temporary folders of dir (`.NAME.tmp-*` beside it whose writer is gone) and
/// returns how many. Never throws.
int remove_stale_temporary_folders(const std::string& dir);

}  // namespace tsp
