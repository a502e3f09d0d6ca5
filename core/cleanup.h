/// Paths aalab has started but not finished: temporary files and DIR.partial folders. When
/// SIGINT or SIGTERM arrives, the signal thread (harness/cli/main.cpp) removes every tracked
/// path and exits, so an interrupted command leaves nothing of its own behind and touches
/// nothing that was there before.
#pragma once
#include <mutex>
#include <string>

namespace aalab {

/// Adds `path` (a file or a folder aalab created) to the unfinished paths.
void TrackUnfinished(const std::string& path);
/// Removes `path` from the unfinished paths (it was committed or cleaned up).
void UntrackUnfinished(const std::string& path);
/// Held while a commit renames finished work into place, so an interruption removes either
/// the unfinished paths before the commit or nothing of the committed result.
std::unique_lock<std::recursive_mutex> LockUnfinished();
/// Removes every tracked path (files, and folders with their content) and keeps the lock for
/// ever, so nothing can be committed or tracked afterwards. Returns how many paths it removed.
/// Called once, by the signal thread, just before the process exits.
int RemoveUnfinishedForExit();

}  // namespace aalab
