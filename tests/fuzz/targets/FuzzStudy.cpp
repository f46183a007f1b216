// libFuzzer target: study files through the path `bounce sweep STUDY.json` takes before any job runs
// (study::loadStudy: strict validation, scenes loaded, every setting applied to a technique from the
// registry, jobs expanded). No job is run: that is bounce render and reference, fuzzed through their
// inputs. Corpus: tests/fuzz/corpus/study; inputs that once failed: tests/fuzz/regressions/study.
#include "../FuzzSupport.h"
#include "app/Study.h"
#include "scene/SceneLoader.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    bounce::fuzz::initializeLoaderTarget();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto path = bounce::fuzz::writeInput("study.json", data, size);
    auto study = bounce::study::loadStudy(path, (bounce::fuzz::scratchFolder() / "out").string());
    (void)study;  // a study or a one-line error: either is fine, a crash or a hang is the finding
    return 0;
}
