// The inputs the fuzzers found interesting (tests/fuzz/corpus), replayed through the same
// harness: each is read without a crash, a sanitizer report or an exception other than
// InputError, and what loads is sound.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "fuzz_target.h"
#include "map/map_reader.h"
#include "test_support.h"

namespace aerobox {

TEST_CASE("the fuzzers' kept inputs read without a crash") {
  const std::filesystem::path corpus = testing::SourceDir() / "tests" / "fuzz" / "corpus";
  int inputs = 0;
  for (const auto& [target, format] :
       {std::pair{"map_txt", MapFormat::kTxt}, std::pair{"map_json", MapFormat::kJson},
        std::pair{"map_csv", MapFormat::kCsv}}) {
    for (const auto& entry : std::filesystem::directory_iterator(corpus / target)) {
      CAPTURE(entry.path());
      std::ifstream in(entry.path(), std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), {});
      const MapFormat f = format;
      fuzz::Run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                [f](std::istream& s) { fuzz::CheckSound(ReadMap(s, "corpus", f)); });
      ++inputs;
    }
  }
  for (const auto& entry : std::filesystem::directory_iterator(corpus / "startgoal")) {
    CAPTURE(entry.path());
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    fuzz::Run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
              [](std::istream& s) {
                const StartGoal sg = ReadStartGoal(s, "corpus");
                fuzz::Require(sg.start.allFinite() && sg.goal.allFinite());
              });
    ++inputs;
  }
  CHECK(inputs >= 25);
}

}  // namespace aerobox
