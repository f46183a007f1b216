#include "core/ImageIo.h"

#include "core/FileIo.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdint>
#include <vector>

namespace bounce {
namespace fs = std::filesystem;

static std::string lowerExtension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

Expected<ImageFormat> imageFormatFor(const fs::path& path) {
    std::string ext = lowerExtension(path);
    if (ext == ".exr") return ImageFormat::Exr;
    if (ext == ".png") return ImageFormat::Png;
    return makeError("{}: unsupported image extension '{}' (use .exr or .png)", path.string(), ext);
}

static Expected<Image> readExr(const fs::path& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int64_t wide = static_cast<int64_t>(dw.max.x) - dw.min.x + 1;
        const int64_t high = static_cast<int64_t>(dw.max.y) - dw.min.y + 1;
        if (wide <= 0 || high <= 0) return makeError("{}: empty EXR data window", path.string());
        // Checked before allocating: a corrupt or hostile header must not ask for gigabytes.
        if (wide > kMaxImageSide || high > kMaxImageSide)
            return makeError("{}: EXR of {}x{} pixels is larger than the {} x {} bounce reads", path.string(), wide, high,
                             kMaxImageSide, kMaxImageSide);
        const int width = static_cast<int>(wide), height = static_cast<int>(high);
        const Imf::ChannelList& channels = file.header().channels();
        const bool hasRgb = channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
        const bool hasY = channels.findChannel("Y");
        if (!hasRgb && !hasY) return makeError("{}: EXR has neither R,G,B nor Y channels", path.string());
        Image image(width, height);
        Imf::FrameBuffer fb;
        // Slice::Make offsets the buffer by the data window's origin itself, in integers. Doing it here,
        // as pointer arithmetic from image.data(), made a pointer outside the image for any window not
        // starting at (0, 0): undefined behaviour (found by fuzz_image under UBSan; a window from y = -1).
        char* base = reinterpret_cast<char*>(image.data());
        const size_t xs = sizeof(glm::vec3), ys = sizeof(glm::vec3) * static_cast<size_t>(width);
        if (hasRgb) {
            fb.insert("R", Imf::Slice::Make(Imf::FLOAT, base + 0, dw, xs, ys));
            fb.insert("G", Imf::Slice::Make(Imf::FLOAT, base + 4, dw, xs, ys));
            fb.insert("B", Imf::Slice::Make(Imf::FLOAT, base + 8, dw, xs, ys));
        } else {
            fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, base + 0, dw, xs, ys));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (!hasRgb)
            for (auto& p : image.pixels()) p = glm::vec3(p.r);
        return image;
    } catch (const std::exception& e) {
        return makeError("{}: cannot read EXR: {}", path.string(), e.what());
    }
}

static Expected<Image> readStb(const fs::path& path) {
    int w = 0, h = 0, n = 0;
    // The header first: a corrupt or hostile one must not make stb_image allocate gigabytes.
    if (!stbi_info(path.c_str(), &w, &h, &n)) return makeError("{}: cannot read image: {}", path.string(), stbi_failure_reason());
    if (w > kMaxImageSide || h > kMaxImageSide)
        return makeError("{}: image of {}x{} pixels is larger than the {} x {} bounce reads", path.string(), w, h, kMaxImageSide,
                         kMaxImageSide);
    stbi_uc* data = stbi_load(path.c_str(), &w, &h, &n, 3);
    if (!data) return makeError("{}: cannot read image: {}", path.string(), stbi_failure_reason());
    Image image(w, h);
    for (size_t i = 0; i < image.pixelCount(); ++i)
        image.data()[i] = {srgbDecode(data[3 * i] / 255.0f), srgbDecode(data[3 * i + 1] / 255.0f),
                           srgbDecode(data[3 * i + 2] / 255.0f)};
    stbi_image_free(data);
    return image;
}

Expected<Image> readImage(const fs::path& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return makeError("{}: file not found", path.string());
    if (fs::is_directory(path, ec)) return makeError("{}: is a directory, not an image", path.string());
    if (std::FILE* f = std::fopen(path.c_str(), "rb")) std::fclose(f);
    else return makeError("{}: cannot open for reading: {}", path.string(), std::strerror(errno));
    if (lowerExtension(path) == ".exr") return readExr(path);
    return readStb(path);
}

namespace {

// OpenEXR writes through this into memory, so the file itself is written (and every write checked)
// by writeFileAtomic: OpenEXR's own file stream reports no error from its final flush and close.
class MemoryOStream : public Imf::OStream {
public:
    MemoryOStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        const size_t end = m_pos + static_cast<size_t>(n);
        if (end > m_bytes.size()) m_bytes.resize(end);
        std::memcpy(m_bytes.data() + m_pos, c, static_cast<size_t>(n));
        m_pos = end;
    }
    uint64_t tellp() override { return m_pos; }
    void seekp(uint64_t pos) override { m_pos = static_cast<size_t>(pos); }
    std::string& bytes() { return m_bytes; }

private:
    std::string m_bytes;
    size_t m_pos = 0;
};

void appendBytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
}

}  // namespace

static Expected<std::string> encodeExr(const Image& image) {
    try {
        MemoryOStream stream;
        {
            Imf::Header header(image.width(), image.height());
            header.channels().insert("R", Imf::Channel(Imf::FLOAT));
            header.channels().insert("G", Imf::Channel(Imf::FLOAT));
            header.channels().insert("B", Imf::Channel(Imf::FLOAT));
            Imf::OutputFile file(stream, header);
            Imf::FrameBuffer fb;
            char* base = const_cast<char*>(reinterpret_cast<const char*>(image.data()));
            const size_t xs = sizeof(glm::vec3), ys = sizeof(glm::vec3) * image.width();
            fb.insert("R", Imf::Slice(Imf::FLOAT, base + 0, xs, ys));
            fb.insert("G", Imf::Slice(Imf::FLOAT, base + 4, xs, ys));
            fb.insert("B", Imf::Slice(Imf::FLOAT, base + 8, xs, ys));
            file.setFrameBuffer(fb);
            file.writePixels(image.height());
        }  // the OutputFile writes its line offset table when destroyed
        return std::move(stream.bytes());
    } catch (const std::exception& e) {
        return makeError("cannot encode EXR: {}", e.what());
    }
}

Expected<std::string> encodeDisplayPng(const Image& display) {
    std::vector<unsigned char> pixels(display.pixelCount() * 3);
    for (size_t i = 0; i < display.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c)
            pixels[3 * i + c] = static_cast<unsigned char>(std::lround(std::clamp(display.data()[i][c], 0.0f, 1.0f) * 255.0f));
    std::string bytes;
    if (!stbi_write_png_to_func(appendBytes, &bytes, display.width(), display.height(), 3, pixels.data(), display.width() * 3))
        return makeError("cannot encode PNG");
    return bytes;
}

Expected<std::string> encodeImage(const fs::path& path, const Image& radiance, const ToneMap& toneMap) {
    BOUNCE_TRY(ImageFormat format, imageFormatFor(path));
    if (radiance.empty()) return makeError("{}: refusing to write an empty image", path.string());
    auto bytes = format == ImageFormat::Exr ? encodeExr(radiance) : encodeDisplayPng(toDisplay(radiance, toneMap));
    if (!bytes.ok()) return makeError("{}: {}", path.string(), bytes.error().message);
    return bytes;
}

Expected<void> writeImage(const fs::path& path, const Image& radiance, const ToneMap& toneMap) {
    BOUNCE_TRY(std::string bytes, encodeImage(path, radiance, toneMap));
    return writeFileAtomic(path, bytes);
}

Expected<void> writeDisplayPng(const fs::path& path, const Image& display) {
    if (lowerExtension(path) != ".png") return makeError("{}: expected a .png path", path.string());
    auto bytes = encodeDisplayPng(display);
    if (!bytes.ok()) return makeError("{}: {}", path.string(), bytes.error().message);
    return writeFileAtomic(path, *bytes);
}

Expected<void> checkFinite(const Image& image, const std::string& what) {
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const glm::vec3 p = image.at(x, y);
            if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b))
                return makeError("{}: non-finite value at pixel ({}, {})", what, x, y);
        }
    return {};
}

}  // namespace bounce
