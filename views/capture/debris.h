// What an interrupted run leaves behind (a capture's .NAME.partial-STAMP-N folder, its .NAME.old-
// folder, a file's .NAME.tmp-STAMP-N, attach's $TMPDIR/gblens-attach-STAMP-XXXXXX): each is named by the
// process that made it, its pid and start time, so a later run removes what a gone process left and
// never what a running one still writes (a reused pid has another start time).
#pragma once
#include <string>
#include <vector>

namespace gb {

// "PID-START": this process's id and its start time (clock ticks after boot, /proc/self/stat).
std::string processStamp();

// Whether the process a name's stamp ("PID-START-...") names has ended: no process of that pid, or
// one started at another time. Names from before stamps had a start time ("PID-N") are judged by
// the pid alone; anything unreadable counts as running (never removed).
bool stampGone(const std::string& stamp);

// Removes the debris of `path` (a capture folder, a report folder, a file) beside it whose process
// is gone; a .NAME.old- folder whose NAME is missing (killed between its two renames) is moved back
// instead. Returns one line per entry, for people ("removed .frame.partial-123-456-7 (process 123 is
// gone)").
std::vector<std::string> removeDebris(const std::string& path);

// The same for names `prefix` + STAMP + anything in `folder` (attach's socket folders in /tmp),
// only those this user owns.
std::vector<std::string> removeDebrisNamed(const std::string& folder, const std::string& prefix);

}  // namespace gb
