// The documented size limits, in-process (the CLI tests check the end-to-end contract for a
// few of them): --size, --threads.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "harness/run/runner.h"

namespace aalab {
namespace {

std::string SizeError(const std::string& text) {
  int w = 0, h = 0;
  try {
    ParseSize(text, &w, &h);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(Limits, FrameSizes) {
  int w = 0, h = 0;
  ParseSize("16384x4096", &w, &h);  // exactly 64 Mpx and the largest side: allowed
  EXPECT_EQ(w, 16384);
  EXPECT_EQ(h, 4096);
  ParseSize("1x1", &w, &h);
  EXPECT_EQ(w * h, 1);
  for (const std::string bad : {"16384x4097",  "16385x16",
                                "16x16385",    "100000x100000",
                                "16384x16384", "0x0",
                                "0x5",         "-5x5",
                                "5x",          "x5",
                                "x",           "",
                                "1e3x5",       "64x36x2",
                                "64 x36",      " 64x36",
                                "64x36 ",      "99999999999999x1",
                                "0x10",        "+5x5",
                                "5x5.0",       "５x5"}) {
    const std::string e = SizeError(bad);
    EXPECT_NE(e.find("--size '" + bad + "'"), std::string::npos) << "'" << bad << "': " << e;
    EXPECT_NE(e.find("W, H <= 16384 and W*H <= 64 Mpx"), std::string::npos) << bad;
  }
}

TEST(Limits, ThreadCounts) {
  for (int bad : {-1, -100, kMaxThreads + 1, 1 << 30}) {
    EXPECT_THROW(SetThreadCount(bad), UserError) << bad;
  }
  SetThreadCount(kMaxThreads);
  SetThreadCount(1);
  EXPECT_EQ(ThreadCount(), 1);
  SetThreadCount(0);
  EXPECT_GE(ThreadCount(), 1);
}

}  // namespace
}  // namespace aalab
