// type = "image": the file is decoded here, at load time (check-config decodes it too, so a file run would refuse
// is refused there), by OpenCV's imgcodecs (libpng, libjpeg-turbo): grey, RGB or RGBA, 8 or 16 bits per channel,
// into premultiplied RGBA. The file's size is checked before it is read and the decoded size before it is kept.
#include "config/config_sections.h"

#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace overlayd::config {

namespace {

constexpr std::uintmax_t kMaxImageFileBytes = 16u << 20;
constexpr int kMaxImageSide = 4096;

std::shared_ptr<const ImagePixels> loadImage(TableReader &table, const std::string &path)
{
    std::error_code error;
    const std::uintmax_t bytes = std::filesystem::file_size(path, error);
    if (error || !std::filesystem::is_regular_file(path, error)) {
        table.problem("path", "cannot read the image " + path + (error ? ": " + error.message() : ""));
        return nullptr;
    }
    if (bytes > kMaxImageFileBytes) {
        table.problem("path", "the image " + path + " has " + std::to_string(bytes) + " bytes; at most " +
                                  std::to_string(kMaxImageFileBytes) + " are read");
        return nullptr;
    }
    cv::Mat decoded;
    try {
        decoded = cv::imread(path, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception &) {
        decoded.release();
    }
    if (decoded.empty()) {
        table.problem("path", "the image " + path + " is not a PNG or JPEG that can be decoded");
        return nullptr;
    }
    if (decoded.cols > kMaxImageSide || decoded.rows > kMaxImageSide) {
        table.problem("path", "the image " + path + " is " + std::to_string(decoded.cols) + "x" +
                                  std::to_string(decoded.rows) + "; at most " + std::to_string(kMaxImageSide) +
                                  " pixels a side");
        return nullptr;
    }
    if (decoded.depth() == CV_16U)
        decoded.convertTo(decoded, CV_8U, 1.0 / 257.0);
    cv::Mat rgba;
    switch (decoded.channels()) {
    case 1:
        cv::cvtColor(decoded, rgba, cv::COLOR_GRAY2RGBA);
        break;
    case 3:
        cv::cvtColor(decoded, rgba, cv::COLOR_BGR2RGBA);
        break;
    case 4:
        cv::cvtColor(decoded, rgba, cv::COLOR_BGRA2RGBA);
        break;
    default:
        table.problem("path", "the image " + path + " has " + std::to_string(decoded.channels()) + " channels");
        return nullptr;
    }
    auto image = std::make_shared<ImagePixels>();
    image->width = unsigned(rgba.cols);
    image->height = unsigned(rgba.rows);
    image->rgba.resize(size_t(rgba.cols) * size_t(rgba.rows) * 4);
    for (int y = 0; y < rgba.rows; ++y) {
        const uint8_t *in = rgba.ptr<uint8_t>(y);
        uint8_t *out = image->rgba.data() + size_t(y) * size_t(rgba.cols) * 4;
        for (int i = 0; i < rgba.cols * 4; i += 4) {
            const unsigned a = in[i + 3];
            for (int c = 0; c < 3; ++c)
                out[i + c] = uint8_t((in[i + c] * a + 127) / 255);
            out[i + 3] = uint8_t(a);
        }
    }
    return image;
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
