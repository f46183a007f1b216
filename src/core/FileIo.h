#pragma once
// File helpers that never leave half-written output: writes go to a temporary file in the same
// folder and are renamed over the target only when complete.
#include "core/Error.h"

#include <filesystem>
#include <functional>
#include <string>

namespace bounce {

Expected<std::string> readTextFile(const std::filesystem::path& path);

// Calls write(tmpPath); on success renames tmpPath to path, otherwise removes tmpPath.
Expected<void> writeFileAtomic(const std::filesystem::path& path,
                               const std::function<Expected<void>(const std::filesystem::path&)>& write);
Expected<void> writeTextFileAtomic(const std::filesystem::path& path, const std::string& text);

// Fails early (before any rendering) when path's folder does not exist or is not writable.
Expected<void> checkWritable(const std::filesystem::path& path);

}  // namespace bounce
