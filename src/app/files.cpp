#include "app/files.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

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

void WriteFileAtomically(const std::string& path, const std::string& text) {
  const fs::path target(path);
  fs::path temporary = target;
  temporary += ".partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw InputError({path, 0}, "", std::string("cannot write: ") + std::strerror(errno));
    }
    out << text;
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw InputError({path, 0}, "", "writing failed (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(temporary, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw InputError({path, 0}, "", "cannot write: " + ec.message());
  }
}

std::string PrepareOutputFolder(const std::string& requested, const std::string& name) {
  const fs::path folder = requested.empty() ? fs::path("renders") / name : fs::path(requested);
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder)) {
    throw InputError({folder.string(), 0}, "--out",
                     "cannot create the output folder: " + ec.message());
  }
  const fs::path probe = folder / ".aerobox-write-test";
  WriteFileAtomically(probe.string(), "");
  fs::remove(probe, ec);
  return folder.string();
}

}  // namespace aerobox
