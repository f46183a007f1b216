// libFuzzer target: `bounce compare`'s image loading and metrics, through the command itself: the
// input is written as an EXR or a PNG and `bounce compare IMAGE IMAGE --json --heatmap H.png` runs on it
// (runCli, as main() calls it), so the decoders, the size and finiteness checks, every metric and the
// heat map see it. The first byte chooses the format ('0' .exr, '1' .png: any byte modulo 2); the rest
// is the file. Corpus: tests/fuzz/corpus/image; inputs that once failed: tests/fuzz/regressions/image.
#include "../FuzzSupport.h"
#include "app/Cli.h"

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // compare's one-line errors go to std::cerr: the fuzzer's log would be one per input. Sanitizer
    // reports are written to the file descriptor, not through the stream, and still reach the log.
    static std::ofstream discard("/dev/null");
    std::cerr.rdbuf(discard.rdbuf());
    bounce::fuzz::scratchFolder();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const auto path = bounce::fuzz::writeInput(data[0] % 2 == 0 ? "image.exr" : "image.png", data + 1, size - 1);
    const std::string heatmap = (bounce::fuzz::scratchFolder() / "heatmap.png").string();
    std::vector<std::string> args = {"bounce", "--log-level", "off", "compare", path.string(), path.string(), "--json",
                                     "--heatmap", heatmap};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    const int rc = bounce::runCli(static_cast<int>(argv.size()), argv.data());
    if (rc != 0 && rc != 1) bounce::fuzz::invariantBroken("bounce compare exited with neither 0 nor 1");
    return 0;
}
