#pragma once
// What the libFuzzer targets share (docs/reliability.md "Fuzzing"). bounce's loaders read files and
// dispatch on the file name's extension, as `bounce render --scene FILE` does, so each input becomes a
// file in a scratch folder of this process, and the loader under test is called on that path: the
// fuzzer reaches exactly the code the command line runs, with no in-memory variant to drift from it.
#include "app/Options.h"
#include "core/Log.h"
#include "scene/SceneLoader.h"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace bounce::fuzz {

// $TMPDIR (or /tmp)/bounce-fuzz-PID (ten digits), created on first use and holding a copy of scenes/models, so that
// scene files in the corpus can place the repository's example models ("models/cube.obj").
inline const std::filesystem::path& scratchFolder() {
    static const std::filesystem::path folder = [] {
        const char* tmp = std::getenv("TMPDIR");
        // The process id zero-padded to a fixed width: input paths appear in error messages, whose
        // formatting is instrumented too, so a path one digit longer would change the coverage the
        // fuzzer steers by, and a seeded run would not repeat from one process to the next.
        char pid[16];
        std::snprintf(pid, sizeof pid, "%010d", static_cast<int>(getpid()));
        std::filesystem::path f = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") / (std::string("bounce-fuzz-") + pid);
        std::filesystem::remove_all(f);
        std::filesystem::create_directories(f);
        std::filesystem::copy(std::filesystem::path(BOUNCE_SOURCE_DIR) / "scenes/models", f / "models",
                              std::filesystem::copy_options::recursive);
        return f;
    }();
    return folder;
}

// Writes the input to scratchFolder()/name (replacing the previous input) and returns the path.
inline std::filesystem::path writeInput(std::string_view name, const uint8_t* data, size_t size) {
    std::filesystem::path path = scratchFolder() / std::string(name);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) std::abort();  // the scratch folder must be writable: a broken harness, not a finding
    return path;
}

// LLVMFuzzerInitialize of the loader targets (scene, model, study): quiet logging (warnings about the
// input are expected and would bury the fuzzer's own log), the application's scene-setting check
// installed as `bounce` installs it, and the scratch folder made before the first input.
inline void initializeLoaderTarget() {
    setLogLevel("off");
    setSceneSettingCheck(checkSceneSetting);
    scratchFolder();
}

// An internal check the fuzzer must treat as a crash: an input that passed bounce's validation and then
// broke something validation exists to prevent.
[[noreturn]] inline void invariantBroken(const char* what) {
    std::fputs(what, stderr);
    std::fputc('\n', stderr);
    std::abort();
}

}  // namespace bounce::fuzz
