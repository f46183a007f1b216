#include "core/ImageIo.h"

#include "core/FileIo.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cmath>
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
        // In 64 bits: the corners may be any ints, so the difference can overflow an int.
        const int64_t width64 = int64_t{dw.max.x} - dw.min.x + 1;
        const int64_t height64 = int64_t{dw.max.y} - dw.min.y + 1;
        if (width64 <= 0 || height64 <= 0) return makeError("{}: empty EXR data window", path.string());
        if (width64 > kMaxImageSide || height64 > kMaxImageSide)
            return makeError("{}: EXR data window is {}x{}; images may be at most {} pixels per side", path.string(),
                             width64, height64, kMaxImageSide);
        const int width = static_cast<int>(width64), height = static_cast<int>(height64);
        const Imf::ChannelList& channels = file.header().channels();
        const bool hasRgb = channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
        const bool hasY = channels.findChannel("Y");
        if (!hasRgb && !hasY) return makeError("{}: EXR has neither R,G,B nor Y channels", path.string());
        Image image(width, height);
        Imf::FrameBuffer fb;
        char* base = reinterpret_cast<char*>(image.data()) -
                     (static_cast<ptrdiff_t>(dw.min.x) + static_cast<ptrdiff_t>(dw.min.y) * width) * sizeof(glm::vec3);
        const size_t xs = sizeof(glm::vec3), ys = sizeof(glm::vec3) * width;
        if (hasRgb) {
            fb.insert("R", Imf::Slice(Imf::FLOAT, base + 0, xs, ys, 1, 1, 0.0));
            fb.insert("G", Imf::Slice(Imf::FLOAT, base + 4, xs, ys, 1, 1, 0.0));
            fb.insert("B", Imf::Slice(Imf::FLOAT, base + 8, xs, ys, 1, 1, 0.0));
        } else {
            fb.insert("Y", Imf::Slice(Imf::FLOAT, base + 0, xs, ys, 1, 1, 0.0));
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
    // The size from the header first: stb_image allocates what the header claims before decoding.
    if (stbi_info(path.c_str(), &w, &h, &n) && (w > kMaxImageSide || h > kMaxImageSide))
        return makeError("{}: image is {}x{}; images may be at most {} pixels per side", path.string(), w, h, kMaxImageSide);
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
    if (lowerExtension(path) == ".exr") return readExr(path);
    return readStb(path);
}

static Expected<void> writeExr(const fs::path& tmp, const Image& image) {
    try {
        Imf::Header header(image.width(), image.height());
        header.channels().insert("R", Imf::Channel(Imf::FLOAT));
        header.channels().insert("G", Imf::Channel(Imf::FLOAT));
        header.channels().insert("B", Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(tmp.c_str(), header);
        Imf::FrameBuffer fb;
        char* base = const_cast<char*>(reinterpret_cast<const char*>(image.data()));
        const size_t xs = sizeof(glm::vec3), ys = sizeof(glm::vec3) * image.width();
        fb.insert("R", Imf::Slice(Imf::FLOAT, base + 0, xs, ys));
        fb.insert("G", Imf::Slice(Imf::FLOAT, base + 4, xs, ys));
        fb.insert("B", Imf::Slice(Imf::FLOAT, base + 8, xs, ys));
        file.setFrameBuffer(fb);
        file.writePixels(image.height());
        return {};
    } catch (const std::exception& e) {
        return makeError("{}: cannot write EXR: {}", tmp.string(), e.what());
    }
}

static Expected<void> writePng(const fs::path& tmp, const Image& display) {
    std::vector<unsigned char> bytes(display.pixelCount() * 3);
    for (size_t i = 0; i < display.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c)
            bytes[3 * i + c] = static_cast<unsigned char>(std::lround(std::clamp(display.data()[i][c], 0.0f, 1.0f) * 255.0f));
    if (!stbi_write_png(tmp.c_str(), display.width(), display.height(), 3, bytes.data(), display.width() * 3))
        return makeError("{}: PNG write failed", tmp.string());
    return {};
}

Expected<void> writeImage(const fs::path& path, const Image& radiance, const ToneMap& toneMap) {
    BOUNCE_TRY(ImageFormat format, imageFormatFor(path));
    if (radiance.empty()) return makeError("{}: refusing to write an empty image", path.string());
    return writeFileAtomic(path, [&](const fs::path& tmp) -> Expected<void> {
        if (format == ImageFormat::Exr) return writeExr(tmp, radiance);
        return writePng(tmp, toDisplay(radiance, toneMap));
    });
}

Expected<void> writeDisplayPng(const fs::path& path, const Image& display) {
    if (lowerExtension(path) != ".png") return makeError("{}: expected a .png path", path.string());
    return writeFileAtomic(path, [&](const fs::path& tmp) { return writePng(tmp, display); });
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
