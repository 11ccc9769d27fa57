#include "fuzz_target.h"
#include "map/map_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return aerobox::fuzz::Run(data, size, [](std::istream& in) {
    aerobox::fuzz::CheckSound(aerobox::ReadMap(in, "fuzz.csv", aerobox::MapFormat::kCsv));
  });
}
