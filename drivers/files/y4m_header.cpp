// SPDX-License-Identifier: Apache-2.0
// YUV4MPEG2 header parameters: W, H, F, C, and the XCOLORRANGE extension; I, A and other X tags are accepted and
// ignored (the frames are progressive pictures to us).
#include "drivers/files/y4m_header.h"

#include <charconv>
#include <cmath>
#include <numeric>

#include "media/frame.h"

namespace overlayd {

namespace {

constexpr std::string_view kMagic = "YUV4MPEG2";

bool parseUnsigned(std::string_view text, unsigned &out)
{
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
    return error == std::errc() && end == text.data() + text.size();
}

Error malformed(const std::string &path, const std::string &why)
{
    return makeError(ErrorCode::Malformed, path + ": Y4M header: " + why);
}

bool parseChroma(std::string_view tag, Y4mHeader &header)
{
    struct Entry {
        std::string_view tag;
        Y4mChroma chroma;
    };
    static constexpr Entry kTags[] = {{"420jpeg", Y4mChroma::C420},  {"420mpeg2", Y4mChroma::C420},
                                      {"420paldv", Y4mChroma::C420}, {"420", Y4mChroma::C420},
                                      {"422", Y4mChroma::C422},      {"444", Y4mChroma::C444},
                                      {"mono", Y4mChroma::Mono}};
    for (const Entry &entry : kTags) {
        if (entry.tag == tag) {
            header.chroma = entry.chroma;
            header.chromaTag = std::string(tag);
            return true;
        }
    }
    return false;
}

Status parseParameter(std::string_view token, Y4mHeader &header, const std::string &path)
{
    const std::string_view value = token.substr(1);
    switch (token[0]) {
    case 'W':
        if (!parseUnsigned(value, header.width))
            return malformed(path, "bad width '" + std::string(token) + "'");
        break;
    case 'H':
        if (!parseUnsigned(value, header.height))
            return malformed(path, "bad height '" + std::string(token) + "'");
        break;
    case 'F': {
        const size_t colon = value.find(':');
        if (colon == std::string_view::npos || !parseUnsigned(value.substr(0, colon), header.fpsNum) ||
            !parseUnsigned(value.substr(colon + 1), header.fpsDen) || header.fpsNum == 0 || header.fpsDen == 0)
            return malformed(path, "bad frame rate '" + std::string(token) + "'");
        break;
    }
    case 'C':
        if (!parseChroma(value, header))
            return makeError(ErrorCode::Unsupported,
                             path + ": Y4M colour space C" + std::string(value) +
                                 " is not supported (C420jpeg, C420mpeg2, C420paldv, C420, C422, C444, Cmono)");
        break;
    case 'X':
        if (value == "COLORRANGE=FULL")
            header.range = ColourRange::Full;
        else if (value == "COLORRANGE=LIMITED")
            header.range = ColourRange::Limited;
        break;
    default: // I (interlacing), A (aspect) and future tags
        break;
    }
    return Ok{};
}

} // namespace

size_t Y4mHeader::frameBytes() const
{
    const size_t luma = size_t(width) * height;
    if (chroma == Y4mChroma::Mono)
        return luma;
    const size_t chromaSamples = size_t((width + hSub() - 1) / hSub()) * ((height + vSub() - 1) / vSub());
    return luma + 2 * chromaSamples;
}

Result<Y4mHeader> parseY4mHeader(std::string_view line, const std::string &path)
{
    if (line.substr(0, kMagic.size()) != kMagic || (line.size() > kMagic.size() && line[kMagic.size()] != ' '))
        return malformed(path, "does not start with YUV4MPEG2");
    Y4mHeader header;
    bool sawWidth = false, sawHeight = false;
    size_t at = kMagic.size();
    while (at < line.size()) {
        const size_t end = std::min(line.find(' ', at + 1), line.size());
        const std::string_view token = line.substr(at + 1, end - at - 1);
        at = end;
        if (token.empty())
            continue;
        sawWidth |= token[0] == 'W', sawHeight |= token[0] == 'H';
        if (auto parsed = parseParameter(token, header, path); !parsed)
            return parsed.error();
    }
    if (!sawWidth || !sawHeight || header.width == 0 || header.height == 0)
        return malformed(path, "needs a width and a height > 0");
    if (header.width > kMaxFrameDimension || header.height > kMaxFrameDimension)
        return malformed(path, std::to_string(header.width) + "x" + std::to_string(header.height) +
                                   " exceeds the limit of " + std::to_string(kMaxFrameDimension) + " per side");
    if (header.frameBytes() > kMaxFrameBytes)
        return malformed(path, std::to_string(header.width) + "x" + std::to_string(header.height) + " C" +
                                   header.chromaTag + " is " + std::to_string(header.frameBytes()) +
                                   " bytes a frame, over the limit of " + std::to_string(kMaxFrameBytes));
    return header;
}

std::string formatY4mHeader(const Y4mHeader &header)
{
    std::string line = "YUV4MPEG2 W" + std::to_string(header.width) + " H" + std::to_string(header.height) + " F" +
                       std::to_string(header.fpsNum) + ":" + std::to_string(header.fpsDen) + " Ip A1:1 C" +
                       header.chromaTag;
    if (header.range)
        line += *header.range == ColourRange::Full ? " XCOLORRANGE=FULL" : " XCOLORRANGE=LIMITED";
    return line + "\n";
}

void fpsToRatio(double fps, unsigned &num, unsigned &den)
{
    if (!(fps > 0.0 && fps < 1e6)) {
        num = 30, den = 1;
        return;
    }
    for (const unsigned candidate : {1u, 1001u}) {
        const double scaled = fps * candidate;
        if (std::abs(scaled - std::round(scaled)) < 1e-3 * candidate / 1000.0 + 1e-9) {
            num = unsigned(std::lround(scaled)), den = candidate;
            return;
        }
    }
    num = unsigned(std::lround(fps * 1e6)), den = 1000000;
    const unsigned divisor = std::gcd(num, den);
    num /= divisor, den /= divisor;
}

} // namespace overlayd
