// SPDX-License-Identifier: Apache-2.0
// What a calibration file may not be: not a regular file, too large, nested too deep, a matrix declared larger (or
// with more channels) than its field needs, a ROS matrix whose data is not a list or disagrees with rows x cols, a
// key given twice. Each refusal names the file and, where the file is at fault, the line.
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "config/calibration.h"
#include "config/nesting_depth.h"

namespace overlayd::test {
namespace {

class CalibrationLimitsTest : public ::testing::Test
{
protected:
    void SetUp() override
    {
        dir_ = std::filesystem::temp_directory_path() /
               ("overlayd-calibration-limits-" + std::to_string(::getpid()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string write(const std::string &name, const std::string &text) const
    {
        const std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }

    // The refusal's message, which must name the file; empty (and a failure) when the file was accepted.
    static std::string refusal(const std::string &path)
    {
        auto c = loadCalibration(path);
        EXPECT_FALSE(c.ok()) << path << " was accepted";
        if (c.ok())
            return {};
        EXPECT_NE(c.error().message.find(path), std::string::npos) << c.error().message;
        return c.error().message;
    }

    std::filesystem::path dir_;
};

// A valid OpenCV file with its distortion matrix's header replaced (rows, cols, dt on lines 12-14).
std::string openCv(const std::string &distortionHeader, const std::string &data = "[ -0.28, 0.09, 0.0008, 0.0, 0.0 ]")
{
    return "%YAML:1.0\n"
           "---\n"
           "image_width: 1280\n"
           "image_height: 720\n"
           "camera_matrix: !!opencv-matrix\n"
           "   rows: 3\n"
           "   cols: 3\n"
           "   dt: d\n"
           "   data: [ 820.0, 0.0, 641.5, 0.0, 818.0, 358.5, 0.0, 0.0, 1.0 ]\n"
           "distortion_coefficients: !!opencv-matrix\n" +
           distortionHeader + "   data: " + data + "\n";
}

// The same as OpenCV writes it in XML (the distortion matrix's rows, cols and dt on lines 12-14).
std::string openCvXml(const std::string &distortionHeader, const std::string &data = "-0.28 0.09 0.0008 0. 0.",
                      const std::string &tail = "")
{
    return "<?xml version=\"1.0\"?>\n"
           "<opencv_storage>\n"
           "<image_width>1280</image_width>\n"
           "<image_height>720</image_height>\n"
           "<camera_matrix type_id=\"opencv-matrix\">\n"
           "  <rows>3</rows>\n"
           "  <cols>3</cols>\n"
           "  <dt>d</dt>\n"
           "  <data>\n"
           "    820. 0. 641.5 0. 818. 358.5 0. 0. 1.</data></camera_matrix>\n"
           "<distortion_coefficients type_id=\"opencv-matrix\">\n" +
           distortionHeader + "  <data>\n    " + data + "</data></distortion_coefficients>\n" + tail +
           "</opencv_storage>\n";
}
const std::string kXmlFive = "  <rows>1</rows>\n  <cols>5</cols>\n  <dt>d</dt>\n";

const std::string kRosHead = "image_width: 640\n"
                             "image_height: 480\n"
                             "camera_matrix:\n"
                             "  rows: 3\n"
                             "  cols: 3\n"
                             "  data: [510.5, 0.25, 322.1, 0, 508.2, 241.7, 0, 0, 1]\n"
                             "distortion_model: plumb_bob\n";

TEST_F(CalibrationLimitsTest, TheValidFilesTheseAreMadeFromLoad)
{
    ASSERT_TRUE(loadCalibration(write("ok.yaml", openCv("   rows: 1\n   cols: 5\n   dt: d\n"))).ok());
    auto ros = loadCalibration(write("ros.yaml", kRosHead + "distortion_coefficients:\n  rows: 1\n  cols: 5\n"
                                                            "  data: [-0.1, 0.02, 0.001, 0.002, 0]\n"));
    ASSERT_TRUE(ros.ok()) << ros.error().message;
    EXPECT_DOUBLE_EQ(ros->distortion.coeffs[1], 0.02);
    auto xml = loadCalibration(write("ok.xml", openCvXml(kXmlFive, "-0.28 0.09 0.0008 0. 0.",
                                                         "<distortion_model>"
                                                         "plumb_bob</distortion_model>\n")));
    ASSERT_TRUE(xml.ok()) << xml.error().message;
    EXPECT_DOUBLE_EQ(xml->distortion.coeffs[1], 0.09);
    EXPECT_DOUBLE_EQ(xml->pinhole.cx, 641.5);
}

// OpenCV's XML read with tinyxml2: each refusal at the element's line.
TEST_F(CalibrationLimitsTest, OpenCvXmlRefusalsNameTheElementsLine)
{
    std::string message = refusal(write("huge.xml", openCvXml("  <rows>100000</rows>\n  <cols>100000</cols>\n  "
                                                              "<dt>d</dt>\n")));
    EXPECT_NE(message.find("huge.xml:11: distortion_coefficients: 100000x100000; it must be 1xN or Nx1"),
              std::string::npos)
        << message;
    message = refusal(write("short.xml", openCvXml(kXmlFive, "1 2 3")));
    EXPECT_NE(message.find("short.xml:11: distortion_coefficients: data must hold rows x cols = 5 numbers, got 3"),
              std::string::npos)
        << message;
    message = refusal(write("word.xml", openCvXml(kXmlFive, "-0.28 0.09 x 0. 0.")));
    EXPECT_NE(message.find("word.xml:15: distortion_coefficients: data holds 'x', not a number"), std::string::npos)
        << message;
    message =
        refusal(write("dup.xml", openCvXml(kXmlFive, "-0.28 0.09 0.0008 0. 0.", "<image_width>640</image_width>\n")));
    EXPECT_NE(message.find("dup.xml:17: 'image_width' given twice (first on line 3)"), std::string::npos) << message;
    std::string wide = openCvXml(kXmlFive);
    wide.replace(wide.find("1280"), 4, "wide");
    message = refusal(write("width.xml", wide));
    EXPECT_NE(message.find("width.xml:3: image_width must be an integer"), std::string::npos) << message;
    message =
        refusal(write("root.xml", "<?xml version=\"1.0\"?>\n\n<storage><image_width>1</image_width></storage>\n"));
    EXPECT_NE(message.find("root.xml:3: not an OpenCV XML file"), std::string::npos) << message;
    message = refusal(write("open.xml", "<?xml version=\"1.0\"?>\n<opencv_storage>\n<image_width>1280\n"));
    EXPECT_NE(message.find("open.xml:"), std::string::npos) << message;
    EXPECT_NE(message.find("does not parse as XML"), std::string::npos) << message;
}

TEST_F(CalibrationLimitsTest, ADirectoryIsCalledADirectory)
{
    std::filesystem::create_directories(dir_ / "cal.yaml");
    const std::string message = refusal((dir_ / "cal.yaml").string());
    EXPECT_NE(message.find("is a directory, not a regular file"), std::string::npos) << message;
    EXPECT_EQ(message.find("does not exist"), std::string::npos) << message;
}

TEST_F(CalibrationLimitsTest, ADeviceIsCalledADeviceAndNotRead)
{
    const std::string message = refusal("/dev/zero");
    EXPECT_NE(message.find("is a character device, not a regular file"), std::string::npos) << message;
}

// Opening a FIFO with no writer blocks an ordinary open(); this one returns (the test would hang otherwise).
TEST_F(CalibrationLimitsTest, AFifoWithNoWriterIsRefusedWithoutBlocking)
{
    const std::string path = (dir_ / "cal.yaml").string();
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    const std::string message = refusal(path);
    EXPECT_NE(message.find("is a FIFO, not a regular file"), std::string::npos) << message;
}

TEST_F(CalibrationLimitsTest, AFileOverTheLimitIsRefusedByItsSize)
{
    const std::string path = write("big.yaml", kRosHead + "# " + std::string(kMaxCalibrationFileBytes, 'x') + "\n");
    const std::string message = refusal(path);
    EXPECT_NE(message.find("at most 1048576 are read"), std::string::npos) << message;
}

TEST_F(CalibrationLimitsTest, DeepNestingIsRefusedAtItsLineBeforeTheParserSeesIt)
{
    // 100000 levels: cv::FileStorage overflows the stack on a few thousand (a crash before this check).
    const std::string flow = "%YAML:1.0\n---\nimage_width: 640\nextra: " + std::string(100000, '[') + "\n";
    std::string message = refusal(write("deep_opencv.yaml", flow));
    EXPECT_NE(message.find("deep_opencv.yaml:4: nested deeper than 64 levels"), std::string::npos) << message;

    std::string xml = "<?xml version=\"1.0\"?>\n<opencv_storage>\n";
    for (int i = 0; i < 100000; ++i)
        xml += "<a>";
    message = refusal(write("deep.xml", xml));
    EXPECT_NE(message.find("deep.xml:3: nested deeper than 64 levels"), std::string::npos) << message;

    std::string block = kRosHead;
    for (int i = 0; i < 100; ++i)
        block += std::string(size_t(i), ' ') + "k:\n";
    message = refusal(write("deep_ros.yaml", block));
    EXPECT_NE(message.find("deep_ros.yaml:" + std::to_string(7 + 65) + ": nested deeper"), std::string::npos)
        << message;
}

// A declared 100000 x 100000 matrix would be an 80 GB allocation with `>> cv::Mat`: refused by its header.
TEST_F(CalibrationLimitsTest, AnOpenCvMatrixLargerThanItsFieldIsRefusedBeforeItsData)
{
    std::string message = refusal(write("huge.yaml", openCv("   rows: 100000\n   cols: 100000\n   dt: d\n")));
    EXPECT_NE(message.find("huge.yaml:10: distortion_coefficients: 100000x100000; it must be 1xN or Nx1 with N = 4, "
                           "5, 8, 12 or 14"),
              std::string::npos)
        << message;
    message = refusal(write("k.yaml", "%YAML:1.0\n---\ncamera_matrix: !!opencv-matrix\n   rows: 30000\n   cols: "
                                      "30000\n   dt: d\n   data: [ 1, 2, 3 ]\n"));
    EXPECT_NE(message.find("k.yaml:3: camera_matrix: 30000x30000; it must be 3x3"), std::string::npos) << message;
    message = refusal(write("short.yaml", openCv("   rows: 1\n   cols: 5\n   dt: d\n", "[ 1, 2, 3 ]")));
    EXPECT_NE(message.find("short.yaml:10: distortion_coefficients: data must hold rows x cols = 5 numbers, got 3"),
              std::string::npos)
        << message;
}

// dt "2d" interleaves two channels: read as one, every other value would land in the wrong coefficient.
TEST_F(CalibrationLimitsTest, ATwoChannelOpenCvMatrixIsRefused)
{
    const std::string message = refusal(write(
        "two.yaml", openCv("   rows: 1\n   cols: 4\n   dt: \"2d\"\n", "[ -0.28, 0.09, 0.0008, 0.0, 0, 0, 0, 0 ]")));
    EXPECT_NE(message.find("two.yaml:10: distortion_coefficients: dt must be one single-channel type"),
              std::string::npos)
        << message;
}

TEST_F(CalibrationLimitsTest, RosDistortionThatIsNotAListIsRefusedAtItsLine)
{
    std::string message =
        refusal(write("scalar.yaml", kRosHead + "distortion_coefficients:\n  rows: 1\n  cols: 5\n  data: -0.1\n"));
    EXPECT_NE(message.find("scalar.yaml:11: distortion_coefficients.data: expected a list of numbers"),
              std::string::npos)
        << message;
    message = refusal(write("mapdata.yaml", kRosHead + "distortion_coefficients: [-0.1, 0.02]\n"));
    EXPECT_NE(message.find("mapdata.yaml:8: distortion_coefficients: expected {rows, cols, data: [...]}"),
              std::string::npos)
        << message;
}

TEST_F(CalibrationLimitsTest, RosRowsAndColsMustAgreeWithTheData)
{
    std::string message = refusal(write(
        "mismatch.yaml", kRosHead + "distortion_coefficients:\n  rows: 1\n  cols: 8\n  data: [-0.1, 0.02, 0, 0, 0]\n"));
    EXPECT_NE(message.find("mismatch.yaml:9: distortion_coefficients: rows x cols = 1x8, but data holds 5 numbers"),
              std::string::npos)
        << message;
    message = refusal(write("k8.yaml", "image_width: 640\nimage_height: 480\ncamera_matrix:\n  rows: 3\n  cols: 3\n"
                                       "  data: [510.5, 0.25, 322.1, 0, 508.2, 241.7, 0, 0]\n"));
    EXPECT_NE(message.find("k8.yaml:4: camera_matrix: rows x cols = 3x3, but data holds 8 numbers"), std::string::npos)
        << message;
}

// yaml-cpp and cv::FileStorage both keep a key given twice and answer with the first: which one was meant?
TEST_F(CalibrationLimitsTest, AKeyGivenTwiceIsRefusedAtItsSecondLine)
{
    std::string message = refusal(write("dup_ros.yaml", kRosHead + "image_width: 1280\n"));
    EXPECT_NE(message.find("dup_ros.yaml:8: 'image_width' given twice (first on line 1)"), std::string::npos)
        << message;
    message = refusal(write("dup_nested.yaml", kRosHead + "distortion_coefficients:\n  rows: 1\n  rows: 1\n"
                                                          "  cols: 2\n  data: [0.1, 0.2]\n"));
    EXPECT_NE(message.find("dup_nested.yaml:10: 'rows' given twice (first on line 9)"), std::string::npos) << message;
    message = refusal(write("dup_opencv.yaml", openCv("   rows: 1\n   cols: 5\n   dt: d\n") + "image_width: 640\n"));
    EXPECT_NE(message.find("dup_opencv.yaml:15: 'image_width' given twice (first on line 3)"), std::string::npos)
        << message;
}

// Found by tests/fuzz/calibration_fuzz (kept there as seeds): cv::FileStorage crashed (SIGSEGV) on a NUL byte in an
// XML file and on a broken XML declaration, threw std::length_error, which escaped the loader (std::terminate), on an
// empty key in a YAML mapping, and looped forever on a 23-byte YAML file (OpenCV YAML is now read with yaml-cpp).
TEST_F(CalibrationLimitsTest, InputsThatCrashedOpenCvAreRefused)
{
    const char nul[] = "<?xml version=\"1.0\"?>\n<opencv_storage>\n<a>\0\0\0</a>\n</opencv_storage>\n";
    std::string message = refusal(write("nul.xml", std::string(nul, sizeof nul - 1)));
    EXPECT_NE(message.find("nul.xml:3: holds a NUL byte"), std::string::npos) << message;
    std::ifstream seed(std::string(OVERLAYD_SOURCE_DIR) + "/tests/fuzz/calibration_seeds/regression_empty_key.yaml",
                       std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(seed)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(text.empty());
    message = refusal(write("empty_key.yaml", text));
    EXPECT_NE(message.find("empty_key.yaml:"), std::string::npos) << message;
    message = refusal(write("loop.yaml", "%YAML:1.0\n---w:3\nide-\nxr"));
    EXPECT_NE(message.find("loop.yaml:"), std::string::npos) << message;
    // cv::FileStorage dereferenced a null pointer on this one (XML is now read with tinyxml2).
    message = refusal(write("declaration.xml", "<?xml versioimagn="));
    EXPECT_NE(message.find("declaration.xml:1: does not parse as XML"), std::string::npos) << message;
}

} // namespace
} // namespace overlayd::test
