#include <iostream>

#include "pipeline/cli/commands.h"

int main(int argc, char** argv) { return fabmesh::cli::run_app(argc, argv, {std::cout, std::cerr}); }
