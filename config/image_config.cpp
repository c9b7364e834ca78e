// type = "image": the file is decoded here, at load time (check-config decodes it too, so a file run would refuse
// is refused there), by media/codec (libpng, libjpeg-turbo): grey, palette, RGB or RGBA, 1 to 16 bits per channel,
// into premultiplied RGBA. The file's size is checked before it is read and the header's image size before any pixel
// is decoded.
#include "config/config_sections.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/regular_file.h"
#include "media/codec/image_codec.h"

namespace overlayd::config {

namespace {

constexpr size_t kMaxImageFileBytes = 16u << 20;
constexpr unsigned kMaxImageSide = 4096;

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

std::shared_ptr<const ImagePixels> loadImage(TableReader &table, const std::string &path)
{
    const auto file = readImageFile(table, path);
    if (!file)
        return nullptr;
    const auto undecodable = [&](const Error &error) {
        table.problem("path",
                      "the image " + path + " is not a PNG or JPEG that can be decoded (" + error.message + ")");
        return nullptr;
    };
    // The header first: an image too large is refused before its pixels are allocated.
    const auto info = readImageInfo(*file);
    if (!info)
        return undecodable(info.error());
    if (info->width > kMaxImageSide || info->height > kMaxImageSide) {
        table.problem("path", "the image " + path + " is " + std::to_string(info->width) + "x" +
                                  std::to_string(info->height) + "; at most " + std::to_string(kMaxImageSide) +
                                  " pixels a side");
        return nullptr;
    }
    const auto decoded = decodeImage(*file, ImageChannels::Rgba, kMaxImageSide);
    if (!decoded)
        return undecodable(decoded.error());
    return premultiplied(*decoded);
}

} // namespace

Shape readImageShape(TableReader &table, const std::string &baseDirectory)
{
    ImageShape s;
    if (auto path = table.string("path"); path && !path->empty())
        s.image = loadImage(table, resolvePath(baseDirectory, *path));
    else if (path)
        table.problem("path", "an empty path");
    else
        table.problem("path", "missing: the PNG or JPEG file, relative to the config's folder");
    s.position = table.vec2("position");
    s.sizePx = table.vec2("size_px");
    s.anchor = table.vec3("anchor");
    if (s.position.has_value() == s.anchor.has_value())
        table.problem(s.position ? "anchor" : "position",
                      "an image needs either position = [x, y] (screen pixels) or anchor = [x, y, z] (world metres), "
                      "not both");
    if (auto size = table.vec2("size")) {
        s.size = *size;
        if (!(size->x > 0 && size->y > 0))
            table.problem("size", "width and height in metres must be > 0");
    } else if (s.anchor) {
        table.problem("size", "missing: [width, height] in metres on the world plane");
    }
    if (s.sizePx && !(s.sizePx->x > 0 && s.sizePx->y > 0))
        table.problem("size_px", "width and height in pixels must be > 0");
    if (s.position && table.has("size"))
        table.problem("size", "a screen image is sized by size_px");
    if (s.anchor && table.has("size_px"))
        table.problem("size_px", "a world image is sized by size (metres)");
    s.axisU = table.vec3("axis_u").value_or(s.axisU);
    s.axisV = table.vec3("axis_v").value_or(s.axisV);
    if (glm::length(glm::cross(s.axisU, s.axisV)) < 1e-9)
        table.problem(table.has("axis_v") ? "axis_v" : "axis_u", "axis_u and axis_v must be non-zero and not parallel");
    s.opacity = table.number("opacity", 0.0, 1.0).value_or(s.opacity);
    return s;
}

} // namespace overlayd::config
