#include "map/read_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace aerobox {
namespace fs = std::filesystem;

std::string ReadTextFile(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError({path, 0}, "", "is a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0}, "", std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError({path, 0}, "", "could not be read");
  return text.str();
}

}  // namespace aerobox
