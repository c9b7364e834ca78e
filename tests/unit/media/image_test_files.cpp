// SPDX-License-Identifier: Apache-2.0
// Helpers of the image codec tests (see the header).
#include "image_test_files.h"

#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>

#include <gtest/gtest.h>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace overlayd::test {

namespace {

// A PNG's rows as its bytes: samples packed most significant bit first below 8 bits, big-endian at 16.
std::vector<uint8_t> packRows(const PngPicture &p)
{
    const size_t perRow = size_t(p.width) * channelsOf(p.colourType);
    const size_t rowBytes = (perRow * size_t(p.bitDepth) + 7) / 8;
    std::vector<uint8_t> bytes(rowBytes * p.height, 0);
    for (size_t y = 0; y < p.height; ++y) {
        uint8_t *row = bytes.data() + y * rowBytes;
        for (size_t i = 0; i < perRow; ++i) {
            const int v = p.samples[y * perRow + i];
            if (p.bitDepth == 16) {
                row[2 * i] = uint8_t(v >> 8);
                row[2 * i + 1] = uint8_t(v);
            } else if (p.bitDepth == 8) {
                row[i] = uint8_t(v);
            } else {
                const size_t bit = i * size_t(p.bitDepth);
                row[bit / 8] |= uint8_t(v << (8 - p.bitDepth - bit % 8));
            }
        }
    }
    return bytes;
}

// setjmp: libpng's default error handler jumps here; only plain data and pointers live in this function.
bool writeWithLibpng(png_structp png, png_infop info, std::FILE *file, const PngPicture *p, png_bytepp rows,
                     const png_color *palette, int entries, const png_color_16 *colour)
{
    if (setjmp(png_jmpbuf(png)))
        return false;
    png_init_io(png, file);
    png_set_IHDR(png, info, p->width, p->height, p->bitDepth, p->colourType,
                 p->interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
                 PNG_FILTER_TYPE_BASE);
    if (entries > 0)
        png_set_PLTE(png, info, palette, entries);
    if (!p->paletteAlpha.empty() || colour)
        png_set_tRNS(png, info, p->paletteAlpha.empty() ? nullptr : p->paletteAlpha.data(), int(p->paletteAlpha.size()),
                     colour);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, info);
    return true;
}

} // namespace

TestFolder::TestFolder()
    : dir(std::filesystem::temp_directory_path() /
          (std::string("overlayd-") + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "-" +
           std::to_string(::getpid())))
{
    std::filesystem::create_directories(dir);
}

TestFolder::~TestFolder()
{
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
}

unsigned channelsOf(int colourType)
{
    switch (colourType) {
    case PNG_COLOR_TYPE_GRAY_ALPHA:
        return 2;
    case PNG_COLOR_TYPE_RGB:
        return 3;
    case PNG_COLOR_TYPE_RGB_ALPHA:
        return 4;
    default: // grey, palette
        return 1;
    }
}

PngPicture randomPicture(unsigned width, unsigned height, int colourType, int bitDepth, bool transparency,
                         unsigned seed)
{
    std::mt19937 random(seed);
    PngPicture p;
    p.width = width;
    p.height = height;
    p.colourType = colourType;
    p.bitDepth = bitDepth;
    const bool palette = colourType == PNG_COLOR_TYPE_PALETTE;
    const int entries = palette ? std::min(1 << bitDepth, 256) : 0;
    const int top = palette ? entries - 1 : (1 << bitDepth) - 1;
    std::uniform_int_distribution<int> sample(0, top), byte(0, 255);
    p.samples.resize(size_t(width) * height * channelsOf(colourType));
    for (int &s : p.samples)
        s = sample(random);
    for (int i = 0; i < entries * 3; ++i)
        p.palette.push_back(uint8_t(byte(random)));
    if (!transparency)
        return p;
    if (palette) {
        for (int i = 0; i < std::max(1, entries / 2); ++i)
            p.paletteAlpha.push_back(uint8_t(byte(random)));
        return p;
    }
    // The colour of the first pixel is the transparent one, and so is every third pixel's.
    const unsigned channels = channelsOf(colourType);
    p.transparentColour.assign(p.samples.begin(), p.samples.begin() + channels);
    for (size_t pixel = 0; pixel < size_t(width) * height; pixel += 3)
        std::copy(p.transparentColour.begin(), p.transparentColour.end(), p.samples.begin() + pixel * channels);
    return p;
}

bool writePng(const std::string &path, const PngPicture &picture)
{
    std::vector<uint8_t> bytes = packRows(picture);
    std::vector<png_bytep> rows(picture.height);
    for (size_t y = 0; y < rows.size(); ++y)
        rows[y] = bytes.data() + y * (bytes.size() / picture.height);
    std::vector<png_color> palette;
    for (size_t i = 0; i + 2 < picture.palette.size(); i += 3)
        palette.push_back({picture.palette[i], picture.palette[i + 1], picture.palette[i + 2]});
    png_color_16 colour{};
    const std::vector<int> &t = picture.transparentColour;
    if (t.size() == 1)
        colour.gray = png_uint_16(t[0]);
    if (t.size() == 3)
        colour = {0, png_uint_16(t[0]), png_uint_16(t[1]), png_uint_16(t[2]), 0};
    std::FILE *file = std::fopen(path.c_str(), "wb");
    if (!file)
        return false;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    const bool written = info && writeWithLibpng(png, info, file, &picture, rows.data(), palette.data(),
                                                 int(palette.size()), t.empty() ? nullptr : &colour);
    png_destroy_write_struct(&png, &info);
    return std::fclose(file) == 0 && written;
}

std::vector<uint8_t> readFile(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeFile(const std::string &path, const std::vector<uint8_t> &bytes)
{
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char *>(bytes.data()), std::streamsize(bytes.size()));
}

cv::Mat openCvRgba(const std::string &path)
{
    cv::Mat decoded = cv::imread(path, cv::IMREAD_UNCHANGED);
    if (decoded.empty())
        return decoded;
    if (decoded.depth() == CV_16U)
        decoded.convertTo(decoded, CV_8U, 1.0 / 257.0);
    cv::Mat rgba;
    const int codes[] = {cv::COLOR_GRAY2RGBA, -1, cv::COLOR_BGR2RGBA, cv::COLOR_BGRA2RGBA};
    cv::cvtColor(decoded, rgba, codes[decoded.channels() - 1]);
    return rgba;
}

cv::Mat openCvRgb(const std::string &path)
{
    cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR), rgb;
    if (!bgr.empty())
        cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    return rgb;
}

cv::Mat asMat(const DecodedImage &image)
{
    const int channels = int(image.channels);
    return cv::Mat(int(image.height), int(image.width), CV_8UC(channels), const_cast<uint8_t *>(image.pixels.data()))
        .clone();
}

int maxDifference(const cv::Mat &a, const cv::Mat &b)
{
    if (a.size() != b.size() || a.type() != b.type())
        return -1;
    cv::Mat difference;
    cv::absdiff(a, b, difference);
    double worst = 0;
    cv::minMaxLoc(difference.reshape(1), nullptr, &worst);
    return int(worst);
}

double psnr(const cv::Mat &a, const cv::Mat &b)
{
    return cv::PSNR(a, b);
}

} // namespace overlayd::test
