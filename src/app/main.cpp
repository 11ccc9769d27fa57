#include <iostream>

#include "app/cli.h"
#include "outputs/interrupt.h"
#include "render/offscreen_context.h"

int main(int argc, char** argv) {
  // first, before any thread: Mesa's disk-cache thread would hold up an interrupted end
  aerobox::DisableShaderDiskCache();
  // Ctrl-C: every long loop stops at its next check, exit 130, no output written or changed
  // (outputs/interrupt.h)
  aerobox::InstallInterruptHandler();
  return aerobox::RunCli(argc, argv, std::cout, std::cerr);
}
