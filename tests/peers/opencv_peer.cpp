// SPDX-License-Identifier: Apache-2.0
// The OpenCV side of scripts/compare-peers.sh: what a user who picks OpenCV writes to draw the comparison scene on
// raw YUYV frames, as a program of its own so that its CPU time is measured like the other tools' (getrusage of
// the child, by the script). Frames are read from a file and written to another, back to back, as the script and
// the other tools lay them out.
//
//   opencv_peer draw  SCENE IN OUT W H N   YUYV -> BGR (cvtColor), cv::line LINE_AA + cv::putText, BGR -> YUYV
//   opencv_peer copy  SCENE IN OUT W H N   read and write only: the same program's cost without drawing
//   opencv_peer png   SCENE OUT.png W H    the scene's lines on a transparent RGBA image (for the overlay peers)
//
// SCENE holds one item a line: `line x0 y0 x1 y1 width r g b` (pixels) or `text x y size_px r g b TEXT` (x, y =
// the text's top-left corner).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace {

struct Item {
    bool isText = false;
    cv::Point2d a, b;   // a line's ends; a text's top-left corner in `a`
    double width = 0.0; // line width, or the text's height in pixels
    cv::Scalar bgr;
    std::string text;
};

bool readScene(const char *path, std::vector<Item> &items)
{
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::string kind;
        double r = 0, g = 0, b = 0;
        Item item;
        fields >> kind;
        if (kind == "line") {
            fields >> item.a.x >> item.a.y >> item.b.x >> item.b.y >> item.width >> r >> g >> b;
        } else if (kind == "text") {
            item.isText = true;
            fields >> item.a.x >> item.a.y >> item.width >> r >> g >> b;
            std::getline(fields >> std::ws, item.text);
        } else {
            continue;
        }
        if (!fields && !item.isText) {
            std::fprintf(stderr, "opencv_peer: %s: cannot read '%s'\n", path, line.c_str());
            return false;
        }
        item.bgr = cv::Scalar(b, g, r);
        items.push_back(item);
    }
    return !items.empty();
}

// cv::line takes integer points with `shift` fractional bits: keep the ends' sub-pixel positions as the others do.
cv::Point fixed(const cv::Point2d &p)
{
    constexpr double kOne = 1 << 4;
    return cv::Point(int(std::lround(p.x * kOne)), int(std::lround(p.y * kOne)));
}

// Hershey glyphs: scale 1 is about 22 px from the top of a capital to the baseline.
void drawItems(cv::Mat &image, const std::vector<Item> &items, bool withText)
{
    for (const Item &item : items) {
        if (!item.isText) {
            cv::line(image, fixed(item.a), fixed(item.b), item.bgr, int(std::lround(item.width)), cv::LINE_AA, 4);
        } else if (withText) {
            const double scale = cv::getFontScaleFromHeight(cv::FONT_HERSHEY_SIMPLEX, int(item.width), 2);
            cv::putText(image, item.text, item.a + cv::Point2d(0, item.width), cv::FONT_HERSHEY_SIMPLEX, scale,
                        item.bgr, 2, cv::LINE_AA);
        }
    }
}

// OpenCV converts BGR to packed 4:4:4 YUV only: the chroma of each pixel pair is averaged into YUYV by hand.
void bgrToYuyv(const cv::Mat &bgr, cv::Mat &yuv, uint8_t *out)
{
    cv::cvtColor(bgr, yuv, cv::COLOR_BGR2YUV);
    for (int y = 0; y < bgr.rows; ++y) {
        const uint8_t *s = yuv.ptr(y);
        uint8_t *d = out + size_t(y) * bgr.cols * 2;
        for (int x = 0; x + 1 < bgr.cols; x += 2, s += 6, d += 4) {
            d[0] = s[0];
            d[1] = uint8_t((s[1] + s[4] + 1) / 2);
            d[2] = s[3];
            d[3] = uint8_t((s[2] + s[5] + 1) / 2);
        }
    }
}

bool readAll(int fd, uint8_t *data, size_t size)
{
    while (size > 0) {
        const ssize_t n = ::read(fd, data, size);
        if (n <= 0)
            return false;
        data += n, size -= size_t(n);
    }
    return true;
}

bool writeAll(int fd, const uint8_t *data, size_t size)
{
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n <= 0)
            return false;
        data += n, size -= size_t(n);
    }
    return true;
}

int runFrames(bool draw, const std::vector<Item> &items, const char *inPath, const char *outPath, int width, int height,
              long frames)
{
    const int in = ::open(inPath, O_RDONLY);
    const int out = ::open(outPath, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0) {
        std::perror("opencv_peer: open");
        return 1;
    }
    cv::Mat yuyv(height, width, CV_8UC2), bgr, yuv;
    const size_t frameBytes = size_t(width) * height * 2;
    for (long i = 0; i < frames; ++i) {
        if (!readAll(in, yuyv.data, frameBytes)) {
            std::fprintf(stderr, "opencv_peer: %s: frame %ld: short read\n", inPath, i);
            return 1;
        }
        if (draw) {
            cv::cvtColor(yuyv, bgr, cv::COLOR_YUV2BGR_YUYV);
            drawItems(bgr, items, true);
            bgrToYuyv(bgr, yuv, yuyv.data);
        }
        if (!writeAll(out, yuyv.data, frameBytes)) {
            std::perror("opencv_peer: write");
            return 1;
        }
    }
    ::close(in);
    ::close(out);
    return 0;
}

// Straight (not premultiplied) RGBA, as PNG and the overlay filters expect: each line drawn as its own coverage
// mask, then composited over what is below it.
int writePng(const std::vector<Item> &items, const char *path, int width, int height)
{
    cv::Mat colour(height, width, CV_32FC3, cv::Scalar::all(0)), alpha(height, width, CV_32F, cv::Scalar(0));
    cv::Mat mask(height, width, CV_8U);
    for (const Item &item : items) {
        if (item.isText)
            continue;
        mask.setTo(0);
        cv::line(mask, fixed(item.a), fixed(item.b), cv::Scalar(255), int(std::lround(item.width)), cv::LINE_AA, 4);
        cv::Mat m;
        mask.convertTo(m, CV_32F, 1.0 / 255);
        const cv::Mat below = alpha.mul(1.0 - m);
        const cv::Mat total = m + below;
        std::vector<cv::Mat> channels;
        cv::split(colour, channels);
        for (int c = 0; c < 3; ++c) {
            cv::Mat blended = (m * item.bgr[c] + channels[c].mul(below));
            cv::divide(blended, cv::max(total, 1e-6), channels[c]);
        }
        cv::merge(channels, colour);
        alpha = total;
    }
    std::vector<cv::Mat> channels;
    cv::split(colour, channels);
    channels.push_back(alpha * 255.0);
    cv::Mat bgra;
    cv::merge(channels, bgra);
    bgra.convertTo(bgra, CV_8UC4);
    return cv::imwrite(path, bgra) ? 0 : 1;
}

} // namespace

int main(int argc, char **argv)
{
    cv::setNumThreads(0); // sequential: every tool of the comparison runs on one core
    const std::string mode = argc > 1 ? argv[1] : "";
    std::vector<Item> items;
    if (mode == "png" && argc == 6 && readScene(argv[2], items))
        return writePng(items, argv[3], std::atoi(argv[4]), std::atoi(argv[5]));
    if ((mode == "draw" || mode == "copy") && argc == 8 && readScene(argv[2], items))
        return runFrames(mode == "draw", items, argv[3], argv[4], std::atoi(argv[5]), std::atoi(argv[6]),
                         std::atol(argv[7]));
    std::fprintf(stderr, "usage: opencv_peer draw|copy SCENE IN OUT WIDTH HEIGHT FRAMES\n"
                         "       opencv_peer png SCENE OUT.png WIDTH HEIGHT\n");
    return 2;
}
