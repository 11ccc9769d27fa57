#include <iostream>

#include "app/cli.h"
#include "outputs/interrupt.h"

int main(int argc, char** argv) {
  // Ctrl-C: the flight stops at its next control step, anything else within a second; only
  // complete files are left (outputs/interrupt.h)
  aerobox::InstallInterruptHandler();
  return aerobox::RunCli(argc, argv, std::cout, std::cerr);
}
