#include "core/FileIo.h"

#include <unistd.h>

#include <fstream>
#include <random>
#include <sstream>

namespace bounce {
namespace fs = std::filesystem;

Expected<std::string> readTextFile(const fs::path& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return makeError("{}: file not found", path.string());
    if (fs::is_directory(path, ec)) return makeError("{}: is a directory, not a file", path.string());
    std::ifstream in(path, std::ios::binary);
    if (!in) return makeError("{}: cannot open for reading", path.string());
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

Expected<void> checkWritable(const fs::path& path) {
    fs::path dir = path.parent_path();
    if (dir.empty()) dir = ".";
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return makeError("{}: folder '{}' does not exist", path.string(), dir.string());
    if (::access(dir.c_str(), W_OK) != 0) return makeError("{}: folder '{}' is not writable", path.string(), dir.string());
    if (fs::is_directory(path, ec)) return makeError("{}: is a directory", path.string());
    return {};
}

Expected<void> writeFileAtomic(const fs::path& path,
                               const std::function<Expected<void>(const fs::path&)>& write) {
    BOUNCE_TRY_VOID(checkWritable(path));
    std::random_device rd;
    // Keep the extension last: some writers pick the format from it.
    fs::path tmp = path.parent_path() /
                   fmt::format(".{}.tmp{:08x}{}", path.stem().string(), rd(), path.extension().string());
    auto result = write(tmp);
    std::error_code ec;
    if (!result.ok()) {
        fs::remove(tmp, ec);
        return result;
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        return makeError("{}: cannot write: {}", path.string(), ec.message());
    }
    return {};
}

Expected<void> writeTextFileAtomic(const fs::path& path, const std::string& text) {
    return writeFileAtomic(path, [&](const fs::path& tmp) -> Expected<void> {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) return makeError("{}: cannot open for writing", path.string());
        out << text;
        out.close();
        if (!out) return makeError("{}: write failed", path.string());
        return {};
    });
}

}  // namespace bounce
