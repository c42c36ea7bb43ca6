// The `rtsim` command. Everything lives in app/cli.cpp; this file sets up the heap's pages and
// Ctrl-C and hands over.
#include "app/cli.hpp"
#include "app/heap_pages.hpp"
#include "app/interrupt_cleanup.hpp"

int main(int argc, char** argv) {
  rtsim::app::use_huge_heap_pages();        // before the simulation's objects are made
  rtsim::app::install_interrupt_cleanup();  // before any thread starts
  return rtsim::app::run_cli(argc, argv);
}
