#include "app/Cli.h"

int main(int argc, char** argv) { return bounce::runCli(argc, argv); }
