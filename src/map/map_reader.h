// Readers for the three published map formats. They take a stream and the file's name (for
// messages); opening files is the caller's business. Every reader returns a validated Map or
// throws InputError naming the file, the line and the field at fault.
#pragma once

#include <istream>
#include <optional>
#include <string>
#include <string_view>

#include "common/error.h"
#include "map/map.h"

namespace aerobox {

enum class MapFormat {
  kTxt,   // MEAM620 2015 / WPI RBE595: "boundary ..." and "block ..." lines
  kJson,  // UPenn flightsim / RotorPy: {"bounds": {"extents": [...]}, "blocks": [...]}
  kCsv,   // Udacity FCND: "lat0 .., lon0 ..", a header, then centre + half-size rows
};

// The format by file extension (.txt, .json, .csv, any case); for other names, by the first
// non-blank character or word of `head` ('{' JSON, "lat0" CSV, anything else TXT).
MapFormat DetectMapFormat(std::string_view file_name, std::string_view head);

// TXT: "boundary xmin ymin zmin xmax ymax zmax [r g b]" once, "block xmin ymin zmin xmax ymax
// zmax [r g b]" any number of times, '#' comments, blank lines, spaces or tabs, CRLF or LF, the
// boundary anywhere in the file. Colours 0-255 or 0-1; the boundary's colour is ignored.
Map ReadTxtMap(std::istream& in, const std::string& file);

// JSON with interleaved extents [xmin, xmax, ymin, ymax, zmin, zmax]; "color" (0-1) optional;
// "start" and "goal" optional; flightsim's other keys (resolution, margin, timeout,
// expected_path_length, algorithms) ignored, any other key an error. The non-standard
// tokens Infinity, -Infinity and NaN are read (and rejected where a finite number is needed).
Map ReadJsonMap(std::istream& in, const std::string& file);

// FCND CSV: line 1 "lat0 <deg>, lon0 <deg>", line 2 the header
// "posX,posY,posZ,halfSizeX,halfSizeY,halfSizeZ", then one box a line (centre and half-sizes,
// metres; X north, Y east, Z up, taken as our x, y, z). The bounds are the union of the boxes.
Map ReadCsvMap(std::istream& in, const std::string& file);

// Reads with the given format; the map's name is the file's stem.
Map ReadMap(std::istream& in, const std::string& file, MapFormat format);
// Reads the file at `path` in the format its name and first bytes say; InputError naming the
// file (and the line) when it cannot.
Map ReadMapFile(const std::string& path);

// Start and goal from a RBE595 "start and goal" file:
//   start: (0, 20, 2)
//   goal:  (10, 20, 3)
// '#' comments and blank lines allowed; both keys required.
struct StartGoal {
  Vec3 start = Vec3::Zero();
  Vec3 goal = Vec3::Zero();
};
StartGoal ReadStartGoal(std::istream& in, const std::string& file);

}  // namespace aerobox
