// The `rtsim` command. Everything lives in app/cli.cpp; this file only hands over.
#include "app/cli.hpp"

int main(int argc, char** argv) { return rtsim::app::run_cli(argc, argv); }
