// What an interrupted run leaves (issue 36, item 4) is removed by the next run once its process is
// gone, judged by pid and start time (views/capture/debris.h): a folder stamped by a process that
// exited is removed (and said), one of a running process is kept, one whose pid now belongs to a
// process started at another time is removed, and an old capture moved aside by a run killed between
// its two renames is moved back.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tests/support/capture_util.h"
#include "views/capture/debris.h"

namespace gb {
namespace {

namespace fs = std::filesystem;

// The stamp of a process that has exited (a child that wrote processStamp() and ended).
std::string goneStamp() {
  int fds[2];
  EXPECT_EQ(pipe(fds), 0);
  const pid_t child = fork();
  if (child == 0) {
    const std::string stamp = processStamp();
    ssize_t ignored = write(fds[1], stamp.data(), stamp.size());
    (void)ignored;
    _exit(0);
  }
  close(fds[1]);
  char buf[64] = {};
  const ssize_t n = read(fds[0], buf, sizeof(buf) - 1);
  close(fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  return std::string(buf, size_t(std::max<ssize_t>(n, 0)));
}

void makeFolder(const fs::path& p) {
  fs::create_directories(p);
  std::ofstream(p / "manifest.json") << "{}";
}

TEST(Debris, RemovedOnceItsProcessIsGoneKeptWhileItRuns) {
  const fs::path root = freshDir("debris");
  const std::string mine = processStamp();
  ASSERT_NE(mine.find('-'), std::string::npos);
  EXPECT_NE(mine.substr(mine.find('-') + 1), "0") << "no start time read from /proc/self/stat";
  const std::string gone = goneStamp(), parent = std::to_string(getppid());
  ASSERT_FALSE(gone.empty());
  ASSERT_NE(gone, mine);

  const fs::path dead = root / (".frame.partial-" + gone + "-17"), alive = root / (".frame.partial-" + mine + "-18");
  // A running process's pid (our parent's) with a start time it does not have: that pid was reused.
  const fs::path reused = root / (".frame.partial-" + parent + "-12345678901-19");
  const fs::path file = root / (".frame.json.tmp-" + gone + "-0.tmp"), other = root / (".other.partial-" + gone + "-20");
  for (const fs::path& p : {dead, alive, reused, other}) makeFolder(p);
  std::ofstream(file) << "half";
  makeFolder(root / "frame");

  const std::vector<std::string> said = removeDebris((root / "frame").string());
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_FALSE(fs::exists(reused));
  EXPECT_TRUE(fs::exists(alive));           // a running process still writes it
  EXPECT_TRUE(fs::exists(other));           // another destination's
  EXPECT_TRUE(fs::exists(root / "frame"));  // the destination itself
  ASSERT_EQ(said.size(), 2u);
  EXPECT_NE(said[0].find("removed "), std::string::npos) << said[0];
  EXPECT_NE(said[0].find(", which is gone)"), std::string::npos) << said[0];

  EXPECT_EQ(removeDebris((root / "frame.json").string()).size(), 1u);  // a file's temporary
  EXPECT_FALSE(fs::exists(file));

  // Killed between moving the old capture aside and renaming the new one in: the old one comes back.
  const fs::path old = root / (".cap.old-" + gone + "-21");
  makeFolder(old);
  const std::vector<std::string> back = removeDebris((root / "cap").string());
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].rfind("moved ", 0), 0u) << back[0];
  EXPECT_TRUE(fs::exists(root / "cap" / "manifest.json"));
  EXPECT_FALSE(fs::exists(old));

  // attach's socket folders: stamped names in a folder, this user's only.
  const fs::path sockets = root / "tmp";
  makeFolder(sockets / ("gblens-attach-" + gone + "-AbC123"));
  makeFolder(sockets / ("gblens-attach-" + mine + "-XyZ789"));
  makeFolder(sockets / "gblens-attach-Qq1234");  // an unstamped name: never judged
  EXPECT_EQ(removeDebrisNamed(sockets.string(), "gblens-attach-").size(), 1u);
  EXPECT_FALSE(fs::exists(sockets / ("gblens-attach-" + gone + "-AbC123")));
  EXPECT_TRUE(fs::exists(sockets / ("gblens-attach-" + mine + "-XyZ789")));
  EXPECT_TRUE(fs::exists(sockets / "gblens-attach-Qq1234"));
}

}  // namespace
}  // namespace gb
