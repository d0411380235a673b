#include "app/cli.hpp"

int main(int argc, char** argv) { return oitbench::run_cli(argc, argv); }
