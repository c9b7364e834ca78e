// SPDX-License-Identifier: Apache-2.0
// Test helpers.
#include "test_util.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>

#include <sys/wait.h>
#include <unistd.h>

namespace overlayd::test {

const PixelFormatInfo &format(const std::string &name)
{
    const PixelFormatInfo *info = pixelFormatFromName(name);
    if (!info)
        throw std::runtime_error("no pixel format " + name);
    return *info;
}

FrameBuffer makeFrame(const std::string &formatName, unsigned width, unsigned height, unsigned stridePadding)
{
    const PixelFormatInfo &info = format(formatName);
    const unsigned stride = stridePadding ? info.minStride(0, width) + stridePadding : 0;
    auto buffer = FrameBuffer::allocate({&info, width, height, stride, {}, 30.0});
    if (!buffer)
        throw std::runtime_error(buffer.error().message);
    return std::move(*buffer);
}

RgbImage blockyImage(unsigned width, unsigned height, unsigned blockW, unsigned blockH, uint32_t seed, bool greyOnly)
{
    std::mt19937 random(seed);
    const unsigned bw = (width + blockW - 1) / blockW, bh = (height + blockH - 1) / blockH;
    std::vector<uint8_t> colours(size_t(bw) * bh * 3);
    for (size_t i = 0; i < colours.size(); i += 3) {
        for (unsigned k = 0; k < 3; ++k)
            colours[i + k] = uint8_t(random() & 0xff);
        if (greyOnly)
            colours[i + 1] = colours[i + 2] = colours[i];
    }
    RgbImage image = RgbImage::allocate(width, height);
    for (unsigned y = 0; y < height; ++y) {
        for (unsigned x = 0; x < width; ++x) {
            const uint8_t *c = &colours[(size_t(y / blockH) * bw + x / blockW) * 3];
            std::copy(c, c + 3, image.row(y) + 3 * x);
        }
    }
    return image;
}

cv::Mat toMat(const RgbImage &image)
{
    return cv::Mat(int(image.height), int(image.width), CV_8UC3, const_cast<uint8_t *>(image.rgb.data()));
}

std::vector<uint8_t> visibleBytes(const FrameView &frame)
{
    std::vector<uint8_t> bytes;
    const PixelFormatInfo &info = *frame.format;
    for (unsigned p = 0; p < info.numPlanes; ++p) {
        for (unsigned y = 0; y < info.planeHeight(p, frame.height); ++y) {
            const uint8_t *row = frame.planes[p].data + size_t(y) * frame.planes[p].stride;
            bytes.insert(bytes.end(), row, row + info.minStride(p, frame.width));
        }
    }
    return bytes;
}

uint64_t hashFrame(const FrameView &frame)
{
    uint64_t hash = 0xcbf29ce484222325ull;
    for (uint8_t byte : visibleBytes(frame))
        hash = (hash ^ byte) * 0x100000001b3ull;
    return hash;
}

TempDir::TempDir()
{
    char pattern[] = "/tmp/overlayd-drivers-XXXXXX";
    if (!mkdtemp(pattern))
        throw std::runtime_error("mkdtemp failed");
    dir_ = pattern;
}

TempDir::~TempDir()
{
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
}

std::string runCommand(const std::string &command, int *status)
{
    std::string output;
    std::FILE *pipe = popen(command.c_str(), "r");
    if (!pipe)
        return output;
    char buffer[4096];
    for (size_t n; (n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0;)
        output.append(buffer, n);
    const int result = pclose(pipe);
    if (status)
        *status = WIFEXITED(result) ? WEXITSTATUS(result) : -1;
    return output;
}

std::vector<uint8_t> readFile(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace overlayd::test
