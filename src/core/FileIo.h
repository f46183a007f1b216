#pragma once
// File helpers that never leave half-written output: writes go to a temporary file in the same
// folder and are renamed over the target only when complete. Every write is checked (a full disk,
// a file-size limit or a failing close is an error naming the output, and its temporary file is
// removed). A target that exists and is not a regular file (a device such as /dev/null or
// /dev/full, a FIFO) is written in place: it cannot be replaced by a rename. A symbolic link is
// followed: the file it points to is replaced, the link kept.
#include "core/Error.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace bounce {

Expected<std::string> readTextFile(const std::filesystem::path& path);

// Writes `bytes` to path atomically (see above).
Expected<void> writeFileAtomic(const std::filesystem::path& path, std::string_view bytes);
Expected<void> writeTextFileAtomic(const std::filesystem::path& path, const std::string& text);

// Outputs that belong together (an image and its run record): every file is written to its
// temporary sibling first and all are renamed only when every write succeeded, so a failure leaves
// none of them (and the previous versions of the targets untouched).
class OutputFiles {
public:
    void add(const std::filesystem::path& path, std::string bytes);
    Expected<void> commit();

private:
    std::vector<std::pair<std::filesystem::path, std::string>> m_files;
};

// Fails early (before any rendering) when path's folder does not exist or a file cannot be created
// in it (probed by creating and removing a temporary file: permission bits do not stop root, a
// read-only file system does), or when path is a folder.
Expected<void> checkWritable(const std::filesystem::path& path);

}  // namespace bounce
