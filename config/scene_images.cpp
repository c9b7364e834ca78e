// SPDX-License-Identifier: Apache-2.0
// SceneImages: PNG and JPEG files to premultiplied RGBA through media/codec (libpng, libjpeg-turbo): grey, palette,
// RGB or RGBA, 1 to 16 bits per channel. The file's size is checked before it is read, the header's image size (and
// the scene's total with it) before any pixel is decoded, and a file already decoded is not read again.
#include "config/scene_images.h"

#include <filesystem>
#include <optional>
#include <vector>

#include "base/regular_file.h"
#include "config/limits.h"
#include "media/codec/image_codec.h"

namespace overlayd {

namespace {

// The file's bytes, after its kind and size were checked; nullopt (with the problem recorded) when it cannot be read.
std::optional<std::vector<uint8_t>> readImageFile(TableReader &table, const std::string &path)
{
    auto file = readRegularFileBytes(path, kMaxImageFileBytes);
    if (!file) {
        table.problem("path", "the image " + path + " " + file.error().message);
        return std::nullopt;
    }
    return std::move(*file);
}

// Straight RGBA to premultiplied, each colour times alpha / 255, rounded.
std::shared_ptr<const ImagePixels> premultiplied(const DecodedImage &decoded)
{
    auto image = std::make_shared<ImagePixels>();
    image->width = decoded.width;
    image->height = decoded.height;
    image->rgba.resize(decoded.pixels.size());
    const uint8_t *in = decoded.pixels.data();
    uint8_t *out = image->rgba.data();
    for (size_t i = 0; i < decoded.pixels.size(); i += 4) {
        const unsigned a = in[i + 3];
        for (size_t c = 0; c < 3; ++c)
            out[i + c] = uint8_t((in[i + c] * a + 127) / 255);
        out[i + 3] = uint8_t(a);
    }
    return image;
}

std::string mebibytes(size_t bytes)
{
    return std::to_string(bytes >> 20) + " MiB";
}

} // namespace

bool SceneImages::withinTotal(TableReader &table, const std::string &path, unsigned width, unsigned height)
{
    if (full_)
        return false; // the annotation that crossed the limit said so; one problem is enough
    const size_t bytes = size_t(width) * height * 4;
    if (totalBytes_ + bytes > kMaxSceneImageBytes) {
        full_ = true;
        table.problem("path", "the image " + path + " (" + std::to_string(width) + "x" + std::to_string(height) + ", " +
                                  mebibytes(bytes) + " decoded) takes the scene's images past " +
                                  mebibytes(kMaxSceneImageBytes) + " (" + mebibytes(totalBytes_) +
                                  " before it; a file shown twice counts twice)");
        return false;
    }
    totalBytes_ += bytes;
    return true;
}

std::shared_ptr<const ImagePixels> SceneImages::load(TableReader &table, const std::string &path)
{
    if (full_)
        return nullptr;
    // "logo.png" and "./logo.png" are one file (a symlink to it is another spelling this does not see).
    const std::string key = std::filesystem::path(path).lexically_normal().string();
    if (const auto known = decoded_.find(key); known != decoded_.end())
        return withinTotal(table, path, known->second->width, known->second->height) ? known->second : nullptr;
    const auto file = readImageFile(table, path);
    if (!file)
        return nullptr;
    const auto undecodable = [&](const Error &error) {
        table.problem("path",
                      "the image " + path + " is not a PNG or JPEG that can be decoded (" + error.message + ")");
        return nullptr;
    };
    // The header first: an image too large, or one too many, is refused before its pixels are allocated.
    const auto info = readImageInfo(*file);
    if (!info)
        return undecodable(info.error());
    if (info->width > kMaxImageSide || info->height > kMaxImageSide) {
        table.problem("path", "the image " + path + " is " + std::to_string(info->width) + "x" +
                                  std::to_string(info->height) + "; at most " + std::to_string(kMaxImageSide) +
                                  " pixels a side");
        return nullptr;
    }
    if (!withinTotal(table, path, info->width, info->height))
        return nullptr;
    const auto decoded = decodeImage(*file, ImageChannels::Rgba, kMaxImageSide);
    if (!decoded)
        return undecodable(decoded.error());
    auto image = premultiplied(*decoded);
    decoded_.emplace(key, image);
    return image;
}

} // namespace overlayd
