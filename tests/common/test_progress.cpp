#include <doctest/doctest.h>

#include <sstream>

#include "common/progress.h"

using aerobox::ProgressDisplay;

TEST_CASE("progress on a terminal is one line, rewritten over what it held, then wiped or kept") {
  std::ostringstream err;
  {
    ProgressDisplay display(err, true, 0.0);
    display.Show("frame 10 of 100");
    display.Show("frame 20");
    CHECK(err.str() == "\rframe 10 of 100\rframe 20       ");
  }
  CHECK(err.str().substr(err.str().size() - 10) == "\r        \r");  // wiped when it ends

  std::ostringstream kept;
  ProgressDisplay display(kept, true, 0.0);
  display.Show("sweep: 4/4 runs");
  display.Keep();
  display.Clear();  // nothing left to wipe
  CHECK(kept.str() == "\rsweep: 4/4 runs\n");
}

TEST_CASE("progress in a log is whole lines, at most one per interval unless forced") {
  std::ostringstream err;
  {
    ProgressDisplay display(err, false, 3600.0);
    display.Show("city queries 1 / 50");
    display.Show("city queries 2 / 50");  // too soon: skipped
    display.Show("timing MuJoCo's steps ...", true);
    display.Keep();
  }
  CHECK(err.str() == "city queries 1 / 50\ntiming MuJoCo's steps ...\n");
}
