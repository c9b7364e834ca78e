// SPDX-License-Identifier: Apache-2.0
// Test frames. The byte orders here are written out from the V4L2 documentation, not read from the format table, so
// that a wrong table entry shows up as a wrong colour.
#include "test_frames.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace overlayd::test {

namespace {

enum class Kind { Packed422, Semi, Planar, Rgb, Grey };

struct Desc {
    Kind kind;
    std::string order; // memory order of a group (packed) or of the chroma planes / interleaved chroma
    unsigned vs = 1;   // chroma vertical subsampling
    int cvCode = -1;   // OpenCV's converter for the format's own memory, -1 when it has none
};

const Desc &desc(const std::string &name)
{
    static const std::map<std::string, Desc> table = {
        {"YUYV", {Kind::Packed422, "YUYV", 1, cv::COLOR_YUV2BGR_YUYV}},
        {"UYVY", {Kind::Packed422, "UYVY", 1, cv::COLOR_YUV2BGR_UYVY}},
        {"YVYU", {Kind::Packed422, "YVYU", 1, cv::COLOR_YUV2BGR_YVYU}},
        {"NV12", {Kind::Semi, "UV", 2, cv::COLOR_YUV2BGR_NV12}},
        {"NV21", {Kind::Semi, "VU", 2, cv::COLOR_YUV2BGR_NV21}},
        {"NV16", {Kind::Semi, "UV", 1, -1}},
        {"YUV420", {Kind::Planar, "UV", 2, cv::COLOR_YUV2BGR_I420}},
        {"YVU420", {Kind::Planar, "VU", 2, cv::COLOR_YUV2BGR_YV12}},
        {"RGB24", {Kind::Rgb, "RGB"}},
        {"BGR24", {Kind::Rgb, "BGR"}},
        {"XRGB32", {Kind::Rgb, "XRGB"}},
        {"XBGR32", {Kind::Rgb, "BGRX"}},
        {"RGBX32", {Kind::Rgb, "RGBX"}},
        {"BGRX32", {Kind::Rgb, "XBGR"}},
        {"ARGB32", {Kind::Rgb, "ARGB"}},
        {"ABGR32", {Kind::Rgb, "BGRA"}},
        {"RGBA32", {Kind::Rgb, "RGBA"}},
        {"BGRA32", {Kind::Rgb, "ABGR"}},
        {"GREY", {Kind::Grey, "Y"}},
    };
    return table.at(name);
}

struct Ycc {
    uint8_t y, u, v;
};

// BT.601-7 / BT.709-6 equations, rounded to the nearest code.
Ycc encode(Colorimetry c, double r, double g, double b)
{
    const bool bt601 = c.matrix == YcbcrMatrix::Bt601;
    const double kr = bt601 ? 0.299 : 0.2126, kb = bt601 ? 0.114 : 0.0722;
    const double y = kr * r + (1 - kr - kb) * g + kb * b;
    const double cb = (b - y) / (2 * (1 - kb)), cr = (r - y) / (2 * (1 - kr));
    const bool limited = c.range == ColourRange::Limited;
    const auto code = [](double v) {
        return uint8_t(std::clamp(std::lround(v), 0L, 255L));
    };
    const double ys = limited ? 219.0 / 255 : 1.0, cs = limited ? 224.0 / 255 : 1.0;
    return {code((limited ? 16 : 0) + ys * y), code(128 + cs * cb), code(128 + cs * cr)};
}

uint8_t chromaByte(char c, Ycc ycc)
{
    return c == 'U' ? ycc.u : ycc.v;
}

} // namespace

bool TestFrame::guardIntact() const
{
    return std::all_of(bytes.end() - kGuardBytes, bytes.end(), [](uint8_t b) { return b == kGuardValue; });
}

const PixelFormatInfo &format(const std::string &name)
{
    const PixelFormatInfo *info = pixelFormatFromName(name);
    if (!info)
        throw std::runtime_error("no format " + name);
    return *info;
}

TestFrame makeFrame(const std::string &formatName, unsigned width, unsigned height, unsigned stridePadding)
{
    const PixelFormatInfo &info = format(formatName);
    auto layout = makeFrameLayout(info, width, height, info.minStride(0, width) + stridePadding);
    if (!layout)
        throw std::runtime_error(layout.error().message);
    TestFrame frame{*layout, std::vector<uint8_t>(layout->totalSize + kGuardBytes, 0x5a)};
    std::fill(frame.bytes.end() - kGuardBytes, frame.bytes.end(), kGuardValue);
    return frame;
}

void fillRgb(TestFrame &frame, Colorimetry colorimetry, uint8_t r, uint8_t g, uint8_t b)
{
    const Desc &d = desc(std::string(frame.layout.format->name));
    const unsigned w = frame.layout.width, h = frame.layout.height;
    const unsigned cw = (w + 1) / 2, ch = (h + d.vs - 1) / d.vs;
    const Ycc ycc = encode(colorimetry, r, g, b);
    for (unsigned y = 0; y < h; ++y) {
        uint8_t *row = frame.plane(0) + y * frame.stride(0);
        if (d.kind == Kind::Rgb) {
            const unsigned bpp = d.order.size();
            for (unsigned x = 0; x < w * bpp; ++x) {
                const char c = d.order[x % bpp];
                row[x] = c == 'R' ? r : c == 'G' ? g : c == 'B' ? b : c == 'A' ? 255 : 0x77;
            }
        } else if (d.kind == Kind::Packed422) {
            for (unsigned x = 0; x < cw * 4; ++x)
                row[x] = d.order[x % 4] == 'Y' ? ycc.y : chromaByte(d.order[x % 4], ycc);
        } else {
            std::memset(row, ycc.y, w);
        }
    }
    for (unsigned y = 0; y < ch && d.kind == Kind::Semi; ++y) {
        for (unsigned x = 0; x < cw * 2; ++x)
            frame.plane(1)[y * frame.stride(1) + x] = chromaByte(d.order[x % 2], ycc);
    }
    for (unsigned y = 0; y < ch && d.kind == Kind::Planar; ++y) {
        std::memset(frame.plane(1) + y * frame.stride(1), chromaByte(d.order[0], ycc), cw);
        std::memset(frame.plane(2) + y * frame.stride(2), chromaByte(d.order[1], ycc), cw);
    }
}

namespace {

cv::Mat rgbToBgr(const TestFrame &frame, const Desc &d)
{
    const unsigned w = frame.layout.width, h = frame.layout.height, bpp = d.order.size();
    cv::Mat bgr(h, w, CV_8UC3);
    for (unsigned y = 0; y < h; ++y) {
        for (unsigned x = 0; x < w; ++x) {
            const uint8_t *px = frame.plane(0) + y * frame.stride(0) + x * bpp;
            cv::Vec3b &out = bgr.at<cv::Vec3b>(y, x);
            out = {px[d.order.find('B')], px[d.order.find('G')], px[d.order.find('R')]};
        }
    }
    return bgr;
}

// Samples of plane p at (x, y) with x, y clamped into the plane: repeats the last column and row.
uint8_t at(const TestFrame &frame, unsigned p, unsigned x, unsigned y, unsigned cols, unsigned rows)
{
    return frame.plane(p)[std::min(y, rows - 1) * frame.stride(p) + std::min(x, cols - 1)];
}

cv::Mat repackedToBgr(const TestFrame &frame, const Desc &d)
{
    const unsigned w = frame.layout.width, h = frame.layout.height;
    const unsigned w2 = w + w % 2, h2 = h + h % 2, cw = (w + 1) / 2, ch = (h + d.vs - 1) / d.vs;
    cv::Mat bgr;
    if (d.vs == 1) { // NV16 -> YUYV
        cv::Mat yuyv(h, w2, CV_8UC2);
        for (unsigned y = 0; y < h; ++y) {
            for (unsigned x = 0; x < w2; ++x) {
                const unsigned cx = (x / 2) * 2 + (x % 2 == 0 ? d.order.find('U') : d.order.find('V'));
                yuyv.at<cv::Vec2b>(y, x) = {at(frame, 0, x, y, w, h), at(frame, 1, cx, y, cw * 2, ch)};
            }
        }
        cv::cvtColor(yuyv, bgr, cv::COLOR_YUV2BGR_YUYV);
    } else { // any 4:2:0 -> I420
        cv::Mat i420(h2 * 3 / 2, w2, CV_8UC1);
        uint8_t *u = i420.ptr(h2), *v = u + (w2 / 2) * (h2 / 2);
        for (unsigned y = 0; y < h2; ++y) {
            for (unsigned x = 0; x < w2; ++x)
                i420.at<uint8_t>(y, x) = at(frame, 0, x, y, w, h);
        }
        for (unsigned y = 0; y < h2 / 2; ++y) {
            for (unsigned x = 0; x < w2 / 2; ++x) {
                const size_t i = y * (w2 / 2) + x;
                if (d.kind == Kind::Semi) {
                    u[i] = at(frame, 1, 2 * x + d.order.find('U'), y, cw * 2, ch);
                    v[i] = at(frame, 1, 2 * x + d.order.find('V'), y, cw * 2, ch);
                } else {
                    u[i] = at(frame, d.order[0] == 'U' ? 1 : 2, x, y, cw, ch);
                    v[i] = at(frame, d.order[0] == 'U' ? 2 : 1, x, y, cw, ch);
                }
            }
        }
        cv::cvtColor(i420, bgr, cv::COLOR_YUV2BGR_I420);
    }
    return bgr(cv::Rect(0, 0, w, h)).clone();
}

} // namespace

cv::Mat toBgr(const TestFrame &frame)
{
    const Desc &d = desc(std::string(frame.layout.format->name));
    const unsigned w = frame.layout.width, h = frame.layout.height;
    uint8_t *base = const_cast<uint8_t *>(frame.plane(0));
    cv::Mat bgr;
    if (d.kind == Kind::Rgb) {
        return rgbToBgr(frame, d);
    } else if (d.kind == Kind::Packed422) {
        // An odd width still has whole 4-byte groups in memory; convert one more column and drop it.
        cv::cvtColor(cv::Mat(h, w + w % 2, CV_8UC2, base, frame.stride(0)), bgr, d.cvCode);
        return bgr(cv::Rect(0, 0, w, h)).clone();
    }
    // OpenCV's padded I420 packs two chroma rows into one luma stride (row 2k + 1 starts W/2 after row 2k), which
    // is not V4L2's layout (chroma stride = stride / 2); the two agree only without padding.
    const bool cvReadsLayout = d.kind == Kind::Semi || frame.stride(0) == w;
    if (d.cvCode >= 0 && w % 2 == 0 && h % 2 == 0 && cvReadsLayout) {
        cv::cvtColor(cv::Mat(h * 3 / 2, w, CV_8UC1, base, frame.stride(0)), bgr, d.cvCode);
        return bgr;
    }
    return repackedToBgr(frame, d);
}

std::vector<cv::Point> pixelsOfByte(const TestFrame &frame, unsigned plane, unsigned row, unsigned column)
{
    const Desc &d = desc(std::string(frame.layout.format->name));
    const int w = frame.layout.width, h = frame.layout.height;
    std::vector<cv::Point> pixels;
    const auto addGroup = [&](int g, int y0, int rows) {
        for (int y = y0; y < std::min(y0 + rows, h); ++y) {
            for (int x = 2 * g; x < std::min(2 * g + 2, w); ++x)
                pixels.push_back({x, y});
        }
    };
    if (d.kind == Kind::Rgb) {
        if (column < w * d.order.size())
            pixels.push_back({int(column / d.order.size()), int(row)});
    } else if (d.kind == Kind::Packed422) {
        const int g = column / 4, x = 2 * g + (d.order.find('Y') == column % 4 ? 0 : 1);
        if (d.order[column % 4] != 'Y')
            addGroup(g, row, 1);
        else if (g < (w + 1) / 2 && x < w)
            pixels.push_back({x, int(row)});
    } else if (plane == 0) {
        if (int(column) < w)
            pixels.push_back({int(column), int(row)});
    } else {
        const unsigned bytesPerGroup = d.kind == Kind::Semi ? 2 : 1;
        if (int(column / bytesPerGroup) < (w + 1) / 2)
            addGroup(column / bytesPerGroup, row * d.vs, d.vs);
    }
    return pixels;
}

char byteKind(const TestFrame &frame, unsigned plane, unsigned column)
{
    const Desc &d = desc(std::string(frame.layout.format->name));
    const unsigned w = frame.layout.width, cw = (w + 1) / 2;
    switch (d.kind) {
    case Kind::Rgb:
        return column < w * d.order.size() ? d.order[column % d.order.size()] : 0;
    case Kind::Packed422:
        return column < cw * 4 ? d.order[column % 4] : 0;
    case Kind::Grey:
        return column < w ? 'Y' : 0;
    case Kind::Semi:
        return plane == 0 ? (column < w ? 'Y' : 0) : (column < cw * 2 ? d.order[column % 2] : 0);
    case Kind::Planar:
        return plane == 0 ? (column < w ? 'Y' : 0) : (column < cw ? d.order[plane - 1] : 0);
    }
    return 0;
}

} // namespace overlayd::test
