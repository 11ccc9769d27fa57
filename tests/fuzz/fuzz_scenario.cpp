#include "fuzz_target.h"
#include "scenario/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return aerobox::fuzz::Run(data, size, [](std::istream& in) {
    const aerobox::Scenario scenario = aerobox::ReadScenario(in, "fuzz.toml");
    aerobox::fuzz::Require(!scenario.map_path.empty());
    if (scenario.start) aerobox::fuzz::Require(scenario.start->allFinite());
    if (scenario.goal) aerobox::fuzz::Require(scenario.goal->allFinite());
    scenario.planning.trajectory.Validate();  // what the reader accepts, the generator takes
  });
}
