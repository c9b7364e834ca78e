// SPDX-License-Identifier: Apache-2.0
// type = "image": the file is decoded at load time into premultiplied RGBA (grey, colour, alpha, 16-bit, JPEG), placed
// on the screen or on a world plane; a file that cannot be used and a placement that is not one of the two are
// refused at their keys; an image too large is refused from its header, before decoding. The test images are written
// by OpenCV's imwrite and the expected pixels worked out here (media/codec's own tests cover every PNG kind).
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include <opencv2/imgcodecs.hpp>

#include "config_test_util.h"

using namespace overlayd;
using overlayd::test::loadInvalid;
using overlayd::test::loadValid;

namespace {

const std::string kScene = R"(
[source]
kind = "synthetic"
width = 640
height = 480
)";

struct ImageFolder {
    // One folder per test and process: CTest runs the tests of this file in parallel.
    std::filesystem::path dir =
        std::filesystem::temp_directory_path() /
        (std::string("overlayd-") + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "-" +
         std::to_string(::getpid()));
    ImageFolder() { std::filesystem::create_directories(dir); }
    ~ImageFolder() { std::filesystem::remove_all(dir); }
    std::string write(const std::string &name, const cv::Mat &image) const
    {
        const std::string path = (dir / name).string();
        EXPECT_TRUE(cv::imwrite(path, image)) << path;
        return path;
    }
};

const ImageShape &imageOf(const DaemonConfig &config, size_t index = 0)
{
    return std::get<ImageShape>(config.scene.annotations.at(index).shape);
}

std::array<uint8_t, 4> pixelOf(const ImagePixels &image, unsigned x, unsigned y)
{
    const uint8_t *p = image.rgba.data() + (size_t(y) * image.width + x) * 4;
    return {p[0], p[1], p[2], p[3]};
}

} // namespace

TEST(ImageConfig, ColourAlphaGreyAnd16BitFilesBecomePremultipliedRgba)
{
    ImageFolder folder;
    cv::Mat bgra(2, 3, CV_8UC4, cv::Scalar(0, 0, 0, 0));
    bgra.at<cv::Vec4b>(0, 0) = {10, 20, 200, 128}; // B G R A
    bgra.at<cv::Vec4b>(1, 2) = {255, 255, 255, 255};
    folder.write("logo.png", bgra);
    cv::Mat grey(4, 4, CV_8UC1, cv::Scalar(77));
    folder.write("grey.png", grey);
    cv::Mat deep(2, 2, CV_16UC3, cv::Scalar(65535, 0, 32896)); // B G R, 16 bits
    folder.write("deep.png", deep);
    folder.write("photo.jpg", cv::Mat(16, 16, CV_8UC3, cv::Scalar(0, 128, 255)));

    const DaemonConfig config = loadValid(kScene + R"(
[[annotation]]
type = "image"
path = "logo.png"
position = [16.0, 20.0]
size_px = [30.0, 20.0]
[[annotation]]
type = "image"
path = "grey.png"
anchor = [1.0, 2.0, 0.0]
size = [2.0, 0.5]
axis_u = [0.0, 1.0, 0.0]
axis_v = [-1.0, 0.0, 0.0]
opacity = 0.5
[[annotation]]
type = "image"
path = "deep.png"
position = [0.0, 0.0]
[[annotation]]
type = "image"
path = "photo.jpg"
position = [0.0, 0.0]
)",
                                          folder.dir.string());
    const ImageShape &logo = imageOf(config, 0);
    ASSERT_TRUE(logo.image);
    EXPECT_EQ(logo.image->width, 3u);
    EXPECT_EQ(logo.image->height, 2u);
    // R 200, G 20, B 10 at alpha 128: each times 128 / 255, rounded.
    EXPECT_EQ(pixelOf(*logo.image, 0, 0), (std::array<uint8_t, 4>{100, 10, 5, 128}));
    EXPECT_EQ(pixelOf(*logo.image, 2, 1), (std::array<uint8_t, 4>{255, 255, 255, 255}));
    EXPECT_EQ(pixelOf(*logo.image, 1, 0), (std::array<uint8_t, 4>{0, 0, 0, 0}));
    EXPECT_EQ(logo.position, glm::dvec2(16.0, 20.0));
    EXPECT_EQ(logo.sizePx, glm::dvec2(30.0, 20.0));
    EXPECT_FALSE(logo.anchor);

    const ImageShape &sign = imageOf(config, 1);
    EXPECT_EQ(pixelOf(*sign.image, 3, 3), (std::array<uint8_t, 4>{77, 77, 77, 255}));
    EXPECT_EQ(sign.anchor, glm::dvec3(1.0, 2.0, 0.0));
    EXPECT_EQ(sign.size, glm::dvec2(2.0, 0.5));
    EXPECT_EQ(sign.axisV, glm::dvec3(-1.0, 0.0, 0.0));
    EXPECT_EQ(sign.opacity, 0.5);

    // 16 bits: 65535 -> 255, 32896 -> 128 (x / 257).
    EXPECT_EQ(pixelOf(*imageOf(config, 2).image, 1, 1), (std::array<uint8_t, 4>{128, 0, 255, 255}));
    const auto jpeg = pixelOf(*imageOf(config, 3).image, 8, 8);
    EXPECT_NEAR(jpeg[0], 255, 3);
    EXPECT_NEAR(jpeg[1], 128, 3);
    EXPECT_NEAR(jpeg[2], 0, 3);
    EXPECT_EQ(jpeg[3], 255);
}

TEST(ImageConfig, EveryRefusalIsAtItsKey)
{
    ImageFolder folder;
    folder.write("ok.png", cv::Mat(2, 2, CV_8UC3, cv::Scalar(1, 2, 3)));
    folder.write("wide.png", cv::Mat(1, 4097, CV_8UC1, cv::Scalar(0)));
    std::ofstream(folder.dir / "text.png") << "not an image\n";
    const auto problems = loadInvalid(kScene + R"(
[[annotation]]
type = "image"
position = [0.0, 0.0]
[[annotation]]
type = "image"
path = "missing.png"
position = [0.0, 0.0]
[[annotation]]
type = "image"
path = "text.png"
position = [0.0, 0.0]
[[annotation]]
type = "image"
path = "wide.png"
position = [0.0, 0.0]
[[annotation]]
type = "image"
path = "ok.png"
position = [0.0, 0.0]
anchor = [0.0, 0.0, 0.0]
[[annotation]]
type = "image"
path = "ok.png"
[[annotation]]
type = "image"
path = "ok.png"
anchor = [0.0, 0.0, 0.0]
size_px = [10.0, 10.0]
opacity = 1.5
axis_u = [1.0, 0.0, 0.0]
axis_v = [2.0, 0.0, 0.0]
[[annotation]]
type = "image"
path = "ok.png"
position = [0.0, 0.0]
size = [1.0, 1.0]
size_px = [0.0, 10.0]
)",
                                      folder.dir.string());
    const std::string all = test::formatProblems(problems);
    const auto has = [&](const std::string &key, const std::string &words) {
        return test::hasProblem(problems, key, words);
    };
    EXPECT_TRUE(has("annotation[0].path", "missing")) << all;
    EXPECT_TRUE(has("annotation[1].path", "missing.png does not exist")) << all;
    EXPECT_TRUE(has("annotation[2].path", "not a PNG or JPEG")) << all;
    EXPECT_TRUE(has("annotation[3].path", "4097x1; at most 4096")) << all;
    EXPECT_TRUE(has("annotation[4].anchor", "not both")) << all;
    EXPECT_TRUE(has("annotation[5].position", "either")) << all;
    EXPECT_TRUE(has("annotation[6].size", "missing")) << all;
    EXPECT_TRUE(has("annotation[6].size_px", "world image")) << all;
    EXPECT_TRUE(has("annotation[6].opacity", "")) << all;
    EXPECT_TRUE(has("annotation[6].axis_v", "not parallel")) << all;
    EXPECT_TRUE(has("annotation[7].size", "size_px")) << all;
    EXPECT_TRUE(has("annotation[7].size_px", "> 0")) << all;
}

TEST(ImageConfig, AnImageTooLargeIsRefusedFromItsHeaderBeforeItIsDecoded)
{
    ImageFolder folder;
    const std::string wide = folder.write("wide.png", cv::Mat(1, 4097, CV_8UC1, cv::Scalar(0)));
    // Cut right after the image data's chunk header: decoding this file could only fail as truncated.
    std::ifstream in(wide, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t idat = bytes.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    std::ofstream(folder.dir / "cut.png", std::ios::binary) << bytes.substr(0, idat + 4);
    const auto problems = loadInvalid(kScene + R"(
[[annotation]]
type = "image"
path = "cut.png"
position = [0.0, 0.0]
)",
                                      folder.dir.string());
    EXPECT_TRUE(test::hasProblem(problems, "annotation[0].path", "4097x1; at most 4096"))
        << test::formatProblems(problems);
}

// One file named by several annotations (however its path is spelled) is decoded once: they share its pixels.
TEST(ImageConfig, TheSameFileIsDecodedOnce)
{
    ImageFolder folder;
    folder.write("a.png", cv::Mat(4, 6, CV_8UC3, cv::Scalar(10, 20, 30)));
    folder.write("b.png", cv::Mat(4, 6, CV_8UC3, cv::Scalar(10, 20, 30)));
    std::string text = kScene;
    for (const char *path : {"a.png", "a.png", "./a.png", "b.png"})
        text += std::string("[[annotation]]\ntype = \"image\"\npath = \"") + path + "\"\nposition = [0.0, 0.0]\n";
    const DaemonConfig config = loadValid(text, folder.dir.string());
    ASSERT_TRUE(imageOf(config, 0).image);
    EXPECT_EQ(imageOf(config, 1).image.get(), imageOf(config, 0).image.get());
    EXPECT_EQ(imageOf(config, 2).image.get(), imageOf(config, 0).image.get());
    EXPECT_NE(imageOf(config, 3).image.get(), imageOf(config, 0).image.get());
}

// What a scene's image annotations decode to is bounded as a whole: four of 4096 x 4096 (64 MiB each) fill
// kMaxSceneImageBytes, the fifth is refused at its path (once: the sixth is not read), one file named five times as
// five files would be.
TEST(ImageConfig, TheScenesDecodedTotalIsBounded)
{
    ImageFolder folder;
    folder.write("big.png", cv::Mat(4096, 4096, CV_8UC1, cv::Scalar(0)));
    std::string text = kScene;
    for (int i = 0; i < 4; ++i)
        text += "[[annotation]]\ntype = \"image\"\npath = \"big.png\"\nposition = [0.0, 0.0]\n";
    loadValid(text, folder.dir.string());
    for (int i = 0; i < 2; ++i)
        text += "[[annotation]]\ntype = \"image\"\npath = \"big.png\"\nposition = [0.0, 0.0]\n";
    const auto problems = loadInvalid(text, folder.dir.string());
    EXPECT_TRUE(test::hasProblem(problems, "annotation[4].path", "past 256 MiB")) << test::formatProblems(problems);
    EXPECT_EQ(problems.size(), 1u) << test::formatProblems(problems);
}
