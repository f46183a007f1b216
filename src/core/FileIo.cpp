#include "core/FileIo.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

namespace bounce {
namespace fs = std::filesystem;

namespace {

// The file a write to `path` replaces: the target of a symbolic link, else path itself.
fs::path resolveTarget(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_symlink(path, ec)) return path;
    fs::path target = fs::read_symlink(path, ec);
    if (ec) return path;
    if (target.is_relative()) target = path.parent_path() / target;
    return target.lexically_normal();
}

// An existing target that is not a regular file (a device, a FIFO) is written in place.
bool writtenInPlace(const fs::path& target) {
    std::error_code ec;
    const fs::file_status status = fs::status(target, ec);
    return !ec && fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status);
}

fs::path folderOf(const fs::path& path) { return path.parent_path().empty() ? fs::path(".") : path.parent_path(); }

fs::path temporarySibling(const fs::path& target) {
    std::random_device rd;
    // Keep the extension last, so the name still says what the file is.
    return folderOf(target) / fmt::format(".{}.tmp{:08x}{}", target.stem().string(), rd(), target.extension().string());
}

// Writes all of `bytes` to `file` (created when `create`), checking every write and the close.
// `name` is the output the user asked for, for messages.
Expected<void> writeBytes(const fs::path& file, std::string_view bytes, bool create, const fs::path& name) {
    const int fd = create ? ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666)
                          : ::open(file.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) return makeError("{}: cannot open for writing: {}", name.string(), std::strerror(errno));
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int e = n < 0 ? errno : ENOSPC;
            ::close(fd);
            return makeError("{}: cannot write: {}", name.string(), std::strerror(e));
        }
        done += static_cast<size_t>(n);
    }
    if (::close(fd) != 0) return makeError("{}: cannot write: {}", name.string(), std::strerror(errno));
    return {};
}

}  // namespace

Expected<std::string> readTextFile(const fs::path& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return makeError("{}: file not found", path.string());
    if (fs::is_directory(path, ec)) return makeError("{}: is a directory, not a file", path.string());
    std::ifstream in(path, std::ios::binary);
    if (!in) return makeError("{}: cannot open for reading: {}", path.string(), std::strerror(errno));
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) return makeError("{}: cannot read", path.string());
    return ss.str();
}

Expected<void> checkWritable(const fs::path& path) {
    const fs::path target = resolveTarget(path);
    std::error_code ec;
    if (fs::is_directory(target, ec)) return makeError("{}: is a directory", path.string());
    if (writtenInPlace(target)) {
        if (::access(target.c_str(), W_OK) != 0)
            return makeError("{}: not writable: {}", path.string(), std::strerror(errno));
        return {};
    }
    const fs::path dir = folderOf(target);
    if (!fs::is_directory(dir, ec)) return makeError("{}: folder '{}' does not exist", path.string(), dir.string());
    // Create and remove a file: the only reliable test (root ignores permission bits, /proc refuses
    // new files to everyone, a read-only mount refuses writes).
    const fs::path probe = temporarySibling(target);
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0)
        return makeError("{}: folder '{}' is not writable: {}", path.string(), dir.string(), std::strerror(errno));
    ::close(fd);
    ::unlink(probe.c_str());
    return {};
}

void OutputFiles::add(const fs::path& path, std::string bytes) { m_files.emplace_back(path, std::move(bytes)); }

Expected<void> OutputFiles::commit() {
    std::vector<std::pair<fs::path, fs::path>> staged;  // temporary file, target
    auto removeStaged = [&] {
        for (const auto& [tmp, target] : staged) ::unlink(tmp.c_str());
    };
    for (const auto& [path, bytes] : m_files) {
        const fs::path target = resolveTarget(path);
        std::error_code ec;
        if (fs::is_directory(target, ec)) {
            removeStaged();
            return makeError("{}: is a directory", path.string());
        }
        if (writtenInPlace(target)) continue;  // below, once every staged file is complete
        if (!fs::is_directory(folderOf(target), ec)) {
            removeStaged();
            return makeError("{}: folder '{}' does not exist", path.string(), folderOf(target).string());
        }
        const fs::path tmp = temporarySibling(target);
        if (auto w = writeBytes(tmp, bytes, true, path); !w.ok()) {
            ::unlink(tmp.c_str());
            removeStaged();
            return w;
        }
        staged.emplace_back(tmp, target);
    }
    for (const auto& [path, bytes] : m_files) {
        const fs::path target = resolveTarget(path);
        if (!writtenInPlace(target)) continue;
        if (auto w = writeBytes(target, bytes, false, path); !w.ok()) {
            removeStaged();
            return w;
        }
    }
    for (size_t i = 0; i < staged.size(); ++i) {
        std::error_code ec;
        fs::rename(staged[i].first, staged[i].second, ec);
        if (ec) {
            for (size_t k = i; k < staged.size(); ++k) ::unlink(staged[k].first.c_str());
            return makeError("{}: cannot write: {}", staged[i].second.string(), ec.message());
        }
    }
    m_files.clear();
    return {};
}

Expected<void> writeFileAtomic(const fs::path& path, std::string_view bytes) {
    OutputFiles files;
    files.add(path, std::string(bytes));
    return files.commit();
}

Expected<void> writeTextFileAtomic(const fs::path& path, const std::string& text) { return writeFileAtomic(path, text); }

}  // namespace bounce
