// Helpers shared by the test binaries.
#pragma once

#include <doctest/doctest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>

namespace aerobox::testing {

inline std::filesystem::path SourceDir() { return AEROBOX_SOURCE_DIR; }

// ../shared/maps beside the checkout, when it is there.
inline std::optional<std::filesystem::path> SharedMapsDir() {
  const std::filesystem::path dir = SourceDir() / ".." / "shared" / "maps";
  std::error_code ec;
  if (std::filesystem::is_directory(dir, ec)) return dir.lexically_normal();
  return std::nullopt;
}

// A fresh folder under the system's temporary folder, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "aerobox-test-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // Writes `text` to `name` inside the folder and returns its full path.
  std::string Write(const std::string& name, const std::string& text) const {
    const std::filesystem::path file = path_ / name;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << text;
    return file.string();
  }

 private:
  std::filesystem::path path_;
};

// The whole file as text ("" when it cannot be read).
inline std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace aerobox::testing

// Ends the current test case as skipped (CTest reads "SKIPPED:") when ../shared/maps is absent.
#define AEROBOX_REQUIRE_SHARED_MAPS(dir_variable)                           \
  const auto dir_variable##_optional = ::aerobox::testing::SharedMapsDir(); \
  if (!dir_variable##_optional) {                                           \
    std::cout << "SKIPPED: ../shared/maps is absent beside the checkout\n"; \
    return;                                                                 \
  }                                                                         \
  const std::filesystem::path dir_variable = *dir_variable##_optional
