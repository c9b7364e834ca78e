// SPDX-License-Identifier: Apache-2.0
// media/codec beyond the PNG matrix: JPEGs OpenCV writes decode as OpenCV decodes them, truncated and corrupt files
// are clear errors (never a crash: CI runs this under ASan), an image too large is refused from its header before
// anything is decoded, and what the snapshot sink encodes reads back through OpenCV (PNG exactly, JPEG within a PSNR
// bound of the picture and of OpenCV's own encoding at the same quality).
#include <turbojpeg.h>
#include <zlib.h>

#include <cstring>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "image_test_files.h"

using namespace overlayd;
using namespace overlayd::test;

namespace {

// A picture with smooth gradients and fine noise: something a JPEG encoder has to work on, in R G B order.
cv::Mat testPicture(int width, int height, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> noise(-12, 12);
    cv::Mat rgb(height, width, CV_8UC3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            rgb.at<cv::Vec3b>(y, x) = {cv::saturate_cast<uint8_t>(x * 255 / width + noise(random)),
                                       cv::saturate_cast<uint8_t>(y * 255 / height + noise(random)),
                                       cv::saturate_cast<uint8_t>(128 + noise(random) * 4)};
    return rgb;
}

RgbImage asRgbImage(const cv::Mat &rgb)
{
    RgbImage image = RgbImage::allocate(unsigned(rgb.cols), unsigned(rgb.rows));
    std::memcpy(image.rgb.data(), rgb.data, image.rgb.size());
    return image;
}

std::string writeJpegWithOpenCv(const TestFolder &folder, const std::string &name, const cv::Mat &image,
                                std::vector<int> parameters = {})
{
    const std::string path = folder.path(name);
    EXPECT_TRUE(cv::imwrite(path, image, parameters)) << path;
    return path;
}

// A PNG chunk: length, type, data, CRC over type and data.
void appendChunk(std::vector<uint8_t> &file, const char *type, const std::vector<uint8_t> &data)
{
    const auto be32 = [&](uint32_t v) {
        for (int shift = 24; shift >= 0; shift -= 8)
            file.push_back(uint8_t(v >> shift));
    };
    be32(uint32_t(data.size()));
    const size_t start = file.size();
    file.insert(file.end(), type, type + 4);
    file.insert(file.end(), data.begin(), data.end());
    be32(uint32_t(crc32(0, file.data() + start, uInt(file.size() - start))));
}

// A PNG that says it is width x height RGB, then ends where its image data would begin: decoding it could only
// fail as truncated, so a refusal that names the size was made from the header alone.
std::vector<uint8_t> headerOnlyPng(uint32_t width, uint32_t height)
{
    std::vector<uint8_t> file = {137, 80, 78, 71, 13, 10, 26, 10};
    std::vector<uint8_t> ihdr;
    for (uint32_t v : {width, height})
        for (int shift = 24; shift >= 0; shift -= 8)
            ihdr.push_back(uint8_t(v >> shift));
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0}); // 8 bits, RGB, deflate, no filter method, not interlaced
    appendChunk(file, "IHDR", ihdr);
    file.insert(file.end(), {0, 0, 0x40, 0, 'I', 'D', 'A', 'T'}); // a 16 KiB IDAT whose data is missing
    return file;
}

} // namespace

TEST(ImageCodec, JpegsDecodeAsOpenCvDecodesThem)
{
    TestFolder folder;
    cv::Mat bgr, grey;
    cv::cvtColor(testPicture(37, 23, 1), bgr, cv::COLOR_RGB2BGR);
    cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
    const std::string paths[] = {
        writeJpegWithOpenCv(folder, "colour.jpg", bgr, {cv::IMWRITE_JPEG_QUALITY, 90}),
        writeJpegWithOpenCv(folder, "grey.jpg", grey),
        writeJpegWithOpenCv(folder, "progressive.jpg", bgr, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}),
    };
    for (const std::string &path : paths) {
        SCOPED_TRACE(path);
        const auto file = readFile(path);
        const auto info = readImageInfo(file);
        ASSERT_TRUE(info) << info.error().message;
        EXPECT_EQ(info->type, ImageFileType::Jpeg);
        EXPECT_EQ(info->width, 37u);
        EXPECT_EQ(info->height, 23u);
        const auto rgb = decodeImage(file, ImageChannels::Rgb, 4096);
        const auto rgba = decodeImage(file, ImageChannels::Rgba, 4096);
        ASSERT_TRUE(rgb) << rgb.error().message;
        ASSERT_TRUE(rgba) << rgba.error().message;
        EXPECT_EQ(maxDifference(asMat(*rgb), openCvRgb(path)), 0);
        EXPECT_EQ(maxDifference(asMat(*rgba), openCvRgba(path)), 0); // alpha 255
    }
}

TEST(ImageCodec, TruncatedAndCorruptFilesAreClearErrors)
{
    TestFolder folder;
    PngPicture picture = randomPicture(64, 64, 2 /* RGB */, 8, false, 5); // noise: a large IDAT
    ASSERT_TRUE(writePng(folder.path("noise.png"), picture));
    const std::vector<uint8_t> png = readFile(folder.path("noise.png"));
    cv::Mat bgr;
    cv::cvtColor(testPicture(64, 48, 2), bgr, cv::COLOR_RGB2BGR);
    const std::vector<uint8_t> jpeg = readFile(writeJpegWithOpenCv(folder, "noise.jpg", bgr));
    for (const auto *whole : {&png, &jpeg}) {
        for (size_t length : {size_t(0), size_t(2), size_t(7), size_t(8), size_t(20), size_t(33), size_t(60),
                              whole->size() / 2, whole->size() - 13, whole->size() - 1}) {
            const std::vector<uint8_t> cut(whole->begin(), whole->begin() + std::ptrdiff_t(length));
            for (ImageChannels channels : {ImageChannels::Rgb, ImageChannels::Rgba}) {
                const auto decoded = decodeImage(cut, channels, 4096);
                ASSERT_FALSE(decoded) << (whole == &png ? "PNG" : "JPEG") << " cut to " << length << " bytes";
                EXPECT_EQ(decoded.error().code, ErrorCode::Malformed) << decoded.error().message;
                EXPECT_GT(decoded.error().message.size(), 10u);
            }
        }
    }
    std::vector<uint8_t> flipped = png;
    flipped[flipped.size() / 2] ^= 0x55; // inside IDAT: its CRC no longer matches
    const auto decoded = decodeImage(flipped, ImageChannels::Rgba, 4096);
    ASSERT_FALSE(decoded);
    EXPECT_NE(decoded.error().message.find("PNG: "), std::string::npos) << decoded.error().message;
    std::vector<uint8_t> scrambled = jpeg;
    std::mt19937 random(3);
    for (size_t i = scrambled.size() / 3; i < scrambled.size() - 2; ++i)
        scrambled[i] = uint8_t(random());
    EXPECT_FALSE(decodeImage(scrambled, ImageChannels::Rgb, 4096));
    const auto text = decodeImage(std::vector<uint8_t>{'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'},
                                  ImageChannels::Rgb, 4096);
    ASSERT_FALSE(text);
    EXPECT_NE(text.error().message.find("neither a PNG nor a JPEG"), std::string::npos) << text.error().message;
}

TEST(ImageCodec, AnImageTooLargeIsRefusedFromItsHeaderBeforeDecoding)
{
    const std::vector<uint8_t> png = headerOnlyPng(20000, 30000); // 1.8 GB of RGB, were it allocated
    const auto info = readImageInfo(png);
    ASSERT_TRUE(info) << info.error().message;
    EXPECT_EQ(info->width, 20000u);
    EXPECT_EQ(info->height, 30000u);
    auto refused = decodeImage(png, ImageChannels::Rgba, 4096);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, ErrorCode::Unsupported);
    EXPECT_NE(refused.error().message.find("20000x30000; at most 4096"), std::string::npos) << refused.error().message;
    // Within the limit the same kind of file is only truncated.
    refused = decodeImage(headerOnlyPng(1000, 1000), ImageChannels::Rgba, 4096);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, ErrorCode::Malformed) << refused.error().message;

    // A JPEG whose frame header says 20000 x 30000, cut off after its first scan's header.
    TestFolder folder;
    cv::Mat bgr;
    cv::cvtColor(testPicture(32, 16, 4), bgr, cv::COLOR_RGB2BGR);
    std::vector<uint8_t> jpeg = readFile(writeJpegWithOpenCv(folder, "small.jpg", bgr));
    size_t sof = 2, sos = 2;
    while (sof + 1 < jpeg.size() && !(jpeg[sof] == 0xff && jpeg[sof + 1] == 0xc0))
        ++sof;
    while (sos + 1 < jpeg.size() && !(jpeg[sos] == 0xff && jpeg[sos + 1] == 0xda))
        ++sos;
    ASSERT_LT(sos + 20, jpeg.size());
    jpeg[sof + 5] = 30000 >> 8, jpeg[sof + 6] = 30000 & 0xff; // height
    jpeg[sof + 7] = 20000 >> 8, jpeg[sof + 8] = 20000 & 0xff; // width
    jpeg.resize(sos + 20);
    const auto jpegInfo = readImageInfo(jpeg);
    ASSERT_TRUE(jpegInfo) << jpegInfo.error().message;
    EXPECT_EQ(jpegInfo->width, 20000u);
    refused = decodeImage(jpeg, ImageChannels::Rgb, 4096);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, ErrorCode::Unsupported) << refused.error().message;
    EXPECT_NE(refused.error().message.find("20000x30000"), std::string::npos) << refused.error().message;
}

TEST(ImageCodec, EncodedPngReadsBackThroughOpenCvExactly)
{
    TestFolder folder;
    const cv::Mat rgb = testPicture(33, 17, 6);
    const auto png = encodePng(asRgbImage(rgb));
    ASSERT_TRUE(png) << png.error().message;
    writeFile(folder.path("snapshot.png"), *png);
    EXPECT_EQ(maxDifference(openCvRgb(folder.path("snapshot.png")), rgb), 0);
    const auto ours = decodeImage(*png, ImageChannels::Rgb, 4096);
    ASSERT_TRUE(ours) << ours.error().message;
    EXPECT_EQ(maxDifference(asMat(*ours), rgb), 0);
}

TEST(ImageCodec, EncodedJpegIsOpenCvsAtTheSameQuality)
{
    TestFolder folder;
    cv::Mat rgb;
    cv::GaussianBlur(testPicture(96, 64, 7), rgb, cv::Size(5, 5), 1.5); // a photo-like picture, for the PSNR bound
    const auto jpeg = encodeJpeg(asRgbImage(rgb), 90);
    ASSERT_TRUE(jpeg) << jpeg.error().message;
    writeFile(folder.path("snapshot.jpg"), *jpeg);
    const cv::Mat decoded = openCvRgb(folder.path("snapshot.jpg"));
    ASSERT_FALSE(decoded.empty());
    EXPECT_GT(psnr(decoded, rgb), 35.0);

    // OpenCV's own encoding of the same picture at the same quality, the snapshot sink's output before media/codec:
    // the same libjpeg-turbo with the same settings, so the same bytes.
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    std::vector<uint8_t> openCvJpeg;
    ASSERT_TRUE(cv::imencode(".jpg", bgr, openCvJpeg, {cv::IMWRITE_JPEG_QUALITY, 90}));
    EXPECT_TRUE(*jpeg == openCvJpeg) << jpeg->size() << " bytes against OpenCV's " << openCvJpeg.size();

    int width = 0, height = 0, subsampling = -1, colourspace = -1;
    tjhandle handle = tjInitDecompress();
    ASSERT_EQ(tjDecompressHeader3(handle, jpeg->data(), jpeg->size(), &width, &height, &subsampling, &colourspace), 0);
    tjDestroy(handle);
    EXPECT_EQ(subsampling, TJSAMP_420);
    EXPECT_EQ(width, 96);
    EXPECT_FALSE(encodeJpeg(asRgbImage(rgb), 0));
    EXPECT_FALSE(encodeJpeg(asRgbImage(rgb), 101));
    EXPECT_FALSE(encodeJpeg(RgbImage{}, 90));
    EXPECT_FALSE(encodePng(RgbImage{}));
}
