// The fcl_quadric command-line program; everything but the process boundary is in cli.cpp.
#include <iostream>

#include "fcl_quadric/cli.h"

int main(int argc, char** argv) { return fcl_quadric::cli::run(argc, argv, std::cout, std::cerr); }
