// SPDX-License-Identifier: Apache-2.0
// Helpers of the drivers tests: owned frames, deterministic test images, hashes, temporary folders, shell-outs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "media/convert/images.h"
#include "media/frame_buffer.h"
#include "media/stream.h"

namespace overlayd::test {

const PixelFormatInfo &format(const std::string &name);
// A frame whose plane 0 stride is padded by stridePadding bytes (0: packed).
FrameBuffer makeFrame(const std::string &formatName, unsigned width, unsigned height, unsigned stridePadding = 0);

// Random colours, constant over aligned blocks of blockW x blockH pixels (2x2 makes chroma averaging irrelevant).
RgbImage blockyImage(unsigned width, unsigned height, unsigned blockW, unsigned blockH, uint32_t seed,
                     bool greyOnly = false);
cv::Mat toMat(const RgbImage &image); // CV_8UC3, R G B order, sharing the pixels

// FNV-1a over the visible bytes of every plane.
uint64_t hashFrame(const FrameView &frame);
std::vector<uint8_t> visibleBytes(const FrameView &frame);

// A fresh folder under the system's temp folder, removed by the destructor.
class TempDir
{
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir &) = delete;
    TempDir &operator=(const TempDir &) = delete;
    std::string path(const std::string &name) const { return (dir_ / name).string(); }

private:
    std::filesystem::path dir_;
};

// stdout of a shell command; exit status in *status.
std::string runCommand(const std::string &command, int *status = nullptr);
std::vector<uint8_t> readFile(const std::string &path);

} // namespace overlayd::test
