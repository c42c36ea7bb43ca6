// The `rtsim` command. Everything lives in app/cli.cpp; this file sets up Ctrl-C and hands over.
#include "app/cli.hpp"
#include "app/interrupt_cleanup.hpp"

int main(int argc, char** argv) {
  rtsim::app::install_interrupt_cleanup();  // before any thread starts
  return rtsim::app::run_cli(argc, argv);
}
