#pragma once
// What the scene-file unit tests share (SceneLoaderTest.cpp: models through assimp;
// JsonSceneFileTest.cpp: JSON scene files; MaterialMapsTest.cpp: glTF materials): a temporary
// folder, file writing and reading, base64 for data URIs, a log capture, look-ups by name.
// The folder is one per process (ctest runs each test in its own process; a test writes its files
// and loads them at once, so test files sharing the folder never read each other's files).
#include "scene/Scene.h"

#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <unistd.h>

namespace bounce::scenefiletest {

namespace fs = std::filesystem;

inline fs::path tempDir() {
    static const fs::path dir = [] {
        fs::path d = fs::temp_directory_path() / ("bounce-scene-file-test-" + std::to_string(::getpid()));
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

inline fs::path writeFile(const std::string& name, const std::string& text) {
    const fs::path p = tempDir() / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
}

inline std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// RFC 4648 base64 (with padding), for glTF data URIs.
inline std::string base64(const std::string& bytes) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8) | uint8_t(bytes[i + 2]);
        for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
    }
    if (i + 1 == bytes.size()) {
        const uint32_t v = uint8_t(bytes[i]) << 16;
        out += std::string{kAlphabet[(v >> 18) & 63], kAlphabet[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == bytes.size()) {
        const uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8);
        out += std::string{kAlphabet[(v >> 18) & 63], kAlphabet[(v >> 12) & 63], kAlphabet[(v >> 6) & 63], '='};
    }
    return out;
}

// Routes spdlog's default logger into a buffer for the lifetime of the object.
class LogCapture {
public:
    LogCapture() : m_sink(std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(128)), m_previous(spdlog::default_logger()) {
        spdlog::set_default_logger(std::make_shared<spdlog::logger>("capture", m_sink));
    }
    ~LogCapture() { spdlog::set_default_logger(m_previous); }
    std::string text() const {
        std::string out;
        for (const std::string& line : m_sink->last_formatted()) out += line;
        return out;
    }

private:
    std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> m_sink;
    std::shared_ptr<spdlog::logger> m_previous;
};

inline const Object* findObject(const Scene& s, const std::string& name) {
    for (const Object& o : s.objects)
        if (o.name == name) return &o;
    return nullptr;
}

inline const Material* findMaterial(const Scene& s, const std::string& name) {
    for (const Material& m : s.materials)
        if (m.name == name) return &m;
    return nullptr;
}

// A unit cube around the origin as OBJ text (quads, no normals).
inline constexpr const char* kCubeObj =
    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 1 2 6 5\nf 4 8 7 3\n";

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace bounce::scenefiletest
