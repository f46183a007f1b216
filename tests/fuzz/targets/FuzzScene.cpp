// libFuzzer target: JSON scene files through the path `bounce render --scene FILE.json` takes
// (loadScene with the application's scene-setting check installed), then exerciseScene on what loaded.
// Corpus: tests/fuzz/corpus/scene; inputs that once failed: tests/fuzz/regressions/scene.
#include "../FuzzSupport.h"
#include "../SceneExercise.h"
#include "scene/SceneLoader.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    bounce::fuzz::initializeLoaderTarget();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto path = bounce::fuzz::writeInput("scene.json", data, size);
    auto scene = bounce::loadScene(path.string());
    if (scene) bounce::fuzz::exerciseScene(*scene);
    return 0;
}
