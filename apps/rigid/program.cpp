// The rigid command-line tool: main() hands the arguments to the command line (main.cpp).
#include <iostream>

#include "command_line.hpp"

int main(int argc, char** argv) {
  return rigid::cli::command_line(argc, argv, std::cout, std::cerr);
}
