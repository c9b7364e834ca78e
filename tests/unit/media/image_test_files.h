// SPDX-License-Identifier: Apache-2.0
// Helpers of the image codec tests: a folder per test, PNGs of any colour type and bit depth written by libpng
// itself, files read back, and OpenCV's imgcodecs as the independent reference.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "media/codec/image_codec.h"

namespace overlayd::test {

// One folder per test and process (CTest runs a program's tests in parallel), removed with its files.
struct TestFolder {
    std::filesystem::path dir;
    TestFolder();
    ~TestFolder();
    std::string path(const std::string &name) const { return (dir / name).string(); }
};

// A PNG as libpng stores it: `samples` holds each row's samples (channels per pixel by colour type; palette
// indices for a palette image), unpacked, one int each; they are packed to the bit depth here.
struct PngPicture {
    unsigned width = 0, height = 0;
    int colourType = 0, bitDepth = 8;
    bool interlaced = false;
    std::vector<int> samples;           // height * width * channels
    std::vector<uint8_t> palette;       // R G B per entry
    std::vector<uint8_t> paletteAlpha;  // tRNS of a palette image: alpha of the first entries
    std::vector<int> transparentColour; // tRNS of a grey (1 value) or RGB (3) image
};

unsigned channelsOf(int colourType);
// Seeded samples over the whole range of the depth, a palette of 2^depth entries (at most 256) where there is one,
// and, with transparency, a tRNS chunk that some pixels match.
PngPicture randomPicture(unsigned width, unsigned height, int colourType, int bitDepth, bool transparency,
                         unsigned seed);
// libpng writes the file; false when it refuses.
bool writePng(const std::string &path, const PngPicture &picture);

std::vector<uint8_t> readFile(const std::string &path);
void writeFile(const std::string &path, const std::vector<uint8_t> &bytes);

// What config/ made of cv::imread(IMREAD_UNCHANGED) before media/codec: 16 bits times 1/257, then RGBA.
cv::Mat openCvRgba(const std::string &path);
// cv::imread(IMREAD_COLOR) in R G B order.
cv::Mat openCvRgb(const std::string &path);
// The decoded pixels as a Mat of 3 or 4 channels (a copy).
cv::Mat asMat(const DecodedImage &image);
// The largest difference of any sample; -1 when the shapes differ.
int maxDifference(const cv::Mat &a, const cv::Mat &b);
double psnr(const cv::Mat &a, const cv::Mat &b);

} // namespace overlayd::test
