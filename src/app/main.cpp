#include <csignal>
#include <iostream>

#include "app/cli.h"
#include "app/fly_job.h"

int main(int argc, char** argv) {
  // Ctrl-C: stop at the next control step and leave only complete files
  std::signal(SIGINT, [](int) { aerobox::RequestStop(); });
  return aerobox::RunCli(argc, argv, std::cout, std::cerr);
}
