#include "app/Cli.h"

#include <csignal>

int main(int argc, char** argv) {
    // A write past the file-size limit (ulimit -f) then fails with EFBIG and is reported as one line
    // naming the output, instead of the signal killing the process with a half-written file.
    std::signal(SIGXFSZ, SIG_IGN);
    return bounce::runCli(argc, argv);
}
