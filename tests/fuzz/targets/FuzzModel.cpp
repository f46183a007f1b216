// libFuzzer target: model files (OBJ, PLY, glTF, GLB) through the path `bounce render --scene FILE`
// takes for a model: bounce's own checks (PLY headers), assimp 5.2, bounce's validation, then
// exerciseScene on what loaded. The first byte chooses the extension, because assimp dispatches on it:
// '0' .obj, '1' .ply, '2' .gltf, '3' .glb (any byte modulo 4); the rest is the file. An OBJ's mtllib
// and a glTF's buffers resolve in the scratch folder (models/ holds the repository's example models).
// Corpus: tests/fuzz/corpus/model; inputs that once failed: tests/fuzz/regressions/model.
#include "../FuzzSupport.h"
#include "../SceneExercise.h"
#include "scene/SceneLoader.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    bounce::fuzz::initializeLoaderTarget();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    static const char* const kNames[] = {"model.obj", "model.ply", "model.gltf", "model.glb"};
    const auto path = bounce::fuzz::writeInput(kNames[data[0] % 4], data + 1, size - 1);
    auto scene = bounce::loadScene(path.string());
    if (scene) bounce::fuzz::exerciseScene(*scene);
    return 0;
}
