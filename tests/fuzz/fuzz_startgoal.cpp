#include "fuzz_target.h"
#include "map/map_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return aerobox::fuzz::Run(data, size, [](std::istream& in) {
    const aerobox::StartGoal sg = aerobox::ReadStartGoal(in, "fuzz.startgoal.txt");
    aerobox::fuzz::Require(sg.start.allFinite() && sg.goal.allFinite());
  });
}
