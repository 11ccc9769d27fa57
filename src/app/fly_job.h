// aerobox fly: plan, solve, fly in MuJoCo, and write the flight's files.
#pragma once

#include <ostream>
#include <string>

#include "outputs/flight_outputs.h"
#include "scenario/scenario.h"

namespace aerobox {

struct FlyOptions {
  std::string out_dir;  // "" : renders/<scenario name>/
  bool video = true;
  bool overview = true;   // overview.png
  bool telemetry = true;  // telemetry.csv
  bool report = true;     // report.html
  std::string command;    // the command line that repeats the run, for report.html
  int width = 640;        // [pixels]
  int height = 480;
  int fps = 30;                  // frames per second of video
  double speed = 1.0;            // playback speed: 2 shows the flight twice as fast
  std::string camera = "chase";  // chase, overview or top
  std::string quality = "fast";  // fast or pretty
  bool progress = true;          // a progress line on standard error when it is a terminal
  double frames_every = 0.0;     // [s] of simulation between PNG frames in frames/ (0: none)
  double telemetry_rate = 0.0;   // [Hz] of telemetry.csv rows (0: every control step)
  bool show_tree = false;        // draw the RRT* tree: growing in the video's first seconds,
                                 // whole in overview.png
};

// Throws InputError naming the option when a value cannot be used: the command checks every
// option before it reads a file or does any work.
void ValidateFlyOptions(const FlyOptions& options);

// What the options ask of the pictures (video, overview, frames).
RenderOptions RenderOptionsFor(const FlyOptions& options);
// Control steps per telemetry row, for a controller at `rate` [Hz] (--telemetry-rate).
int TelemetryEvery(const FlyOptions& options, double rate);
// The command that repeats the run, as report.html shows it.
std::string ReportCommand(const FlyOptions& options, const FlightSetup& setup);

// Runs the whole job and returns the exit code (app/exit_codes.h). Throws InputError for bad
// input, before anything is written.
int RunFly(const FlightSetup& setup, const FlyOptions& options, std::ostream& out,
           std::ostream& err);

}  // namespace aerobox
