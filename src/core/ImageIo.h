#pragma once
// Reading and writing images. EXR holds linear radiance (32-bit float RGB); PNG holds the
// tone-mapped display image (8-bit sRGB). Writes are atomic and checked (core/FileIo.h): an error
// leaves no file behind.
#include "core/Error.h"
#include "core/Image.h"
#include "core/ToneMap.h"

#include <filesystem>

namespace bounce {

enum class ImageFormat { Exr, Png };

// kMaxImageSide (core/Image.h): the largest image side bounce reads, renders or writes.

// Picks the format from the extension (.exr, .png); anything else is an error naming the path.
Expected<ImageFormat> imageFormatFor(const std::filesystem::path& path);

// EXR: linear values as stored. PNG/JPEG/HDR (through stb_image): 8-bit values are decoded from
// sRGB to linear, so writing them back with ToneCurve::Clamp at 0 EV reproduces the file.
Expected<Image> readImage(const std::filesystem::path& path);

// The bytes of the file writeImage writes (format from the extension), for OutputFiles.
Expected<std::string> encodeImage(const std::filesystem::path& path, const Image& radiance, const ToneMap& toneMap = {});
Expected<std::string> encodeDisplayPng(const Image& display);

// EXR: writes `radiance` as is. PNG: writes toDisplay(radiance, toneMap).
Expected<void> writeImage(const std::filesystem::path& path, const Image& radiance, const ToneMap& toneMap = {});

// Writes an already display-encoded image ([0,1] values, no tone map) as PNG.
Expected<void> writeDisplayPng(const std::filesystem::path& path, const Image& display);

// Any non-finite pixel is an input error (texture or image file); returns the first offender.
Expected<void> checkFinite(const Image& image, const std::string& what);

}  // namespace bounce
