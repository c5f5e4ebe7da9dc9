// The viewer's key table is one table: the README's input table is exactly what `gblens view --keys`
// prints from views/ui/keys.cpp (the table the key handler dispatches through and Help shows), so the
// README cannot drift from the keys the viewer has.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/support/capture_util.h"
#include "tests/support/test_paths.h"

namespace gb {

TEST(Keys, TheReadmesInputTableIsTheViewersKeyTable) {
  std::ifstream in(GBLENS_SOURCE_DIR + "/README.md");
  ASSERT_TRUE(in) << "README.md";
  std::stringstream text;
  text << in.rdbuf();
  const std::string readme = text.str();
  const std::string open = "<!-- keys:", close = "<!-- /keys -->";
  const size_t a = readme.find(open), b = readme.find(close);
  ASSERT_NE(a, std::string::npos) << "README.md has no key table marker";
  ASSERT_NE(b, std::string::npos);
  const size_t body = readme.find('\n', a) + 1;
  const std::string table = readme.substr(body, b - body);
  RunResult r = runGblens("view --keys");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(table, r.output) << "README.md's key table differs from `gblens view --keys`: paste its output between the markers";
  // Every key the handler knows has a row: the seed's view keys and the viewer's own.
  for (const char* key : {"`1`", "`0, Return`", "`2..9`", "`Space`", "`G`", "`Z`", "`ctrl+Q`", "`arrows`"})
    EXPECT_NE(table.find(key), std::string::npos) << key;
}

}  // namespace gb
