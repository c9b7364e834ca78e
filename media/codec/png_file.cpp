// SPDX-License-Identifier: Apache-2.0
// PNG through libpng's classic API. libpng reports an error by longjmp back to the last setjmp: the three functions
// that call setjmp (readHeader, readRows, writeRows) hold only plain data and pointers, so the jump skips no
// destructor; every C++ object (the handles' owners, the pixels, the row pointers) lives in their callers.
#include "media/codec/formats.h"
#include "media/codec/image_codec.h"

#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>

namespace overlayd {

namespace {

// What libpng's callbacks reach through their user pointers: plain data.
struct PngIo {
    const uint8_t *data = nullptr;
    size_t size = 0, offset = 0;
    std::vector<uint8_t> *out = nullptr; // encoding
    char message[192] = "";
};

[[noreturn]] void onError(png_structp png, png_const_charp message)
{
    auto *io = static_cast<PngIo *>(png_get_error_ptr(png));
    std::snprintf(io->message, sizeof io->message, "%s", message);
    png_longjmp(png, 1);
}

// Warnings are about chunks that do not change the pixels (a bad gamma or ICC profile, text): not ours to judge.
void onWarning(png_structp, png_const_charp) {}

void readBytes(png_structp png, png_bytep out, size_t length)
{
    auto *io = static_cast<PngIo *>(png_get_io_ptr(png));
    if (length > io->size - io->offset)
        png_error(png, "the file ends early (truncated)");
    std::memcpy(out, io->data + io->offset, length);
    io->offset += length;
}

void writeBytes(png_structp png, png_bytep data, size_t length)
{
    auto *io = static_cast<PngIo *>(png_get_io_ptr(png));
    bool stored = true;
    try {
        io->out->insert(io->out->end(), data, data + length);
    } catch (const std::bad_alloc &) {
        stored = false; // no exception may cross libpng's C frames
    }
    if (!stored)
        png_error(png, "out of memory");
}

struct ReadHandles {
    png_structp png = nullptr;
    png_infop info = nullptr;

    explicit ReadHandles(PngIo &io)
    {
        png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &io, onError, onWarning);
        if (png) {
            info = png_create_info_struct(png);
            png_set_read_fn(png, &io, readBytes);
        }
    }
    ~ReadHandles() { png_destroy_read_struct(&png, &info, nullptr); }
    ReadHandles(const ReadHandles &) = delete;
    ReadHandles &operator=(const ReadHandles &) = delete;
};

struct WriteHandles {
    png_structp png = nullptr;
    png_infop info = nullptr;

    explicit WriteHandles(PngIo &io)
    {
        png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &io, onError, onWarning);
        if (png) {
            info = png_create_info_struct(png);
            png_set_write_fn(png, &io, writeBytes, nullptr);
        }
    }
    ~WriteHandles() { png_destroy_write_struct(&png, &info); }
    WriteHandles(const WriteHandles &) = delete;
    WriteHandles &operator=(const WriteHandles &) = delete;
};

struct PngHeader {
    png_uint_32 width = 0, height = 0;
    int bitDepth = 0, colourType = 0;
    bool transparency = false; // a tRNS chunk
};

// setjmp: plain data only (see the top of the file).
bool readHeader(png_structp png, png_infop info, PngHeader *header)
{
    if (setjmp(png_jmpbuf(png)))
        return false;
    png_read_info(png, info);
    png_get_IHDR(png, info, &header->width, &header->height, &header->bitDepth, &header->colourType, nullptr, nullptr,
                 nullptr);
    header->transparency = png_get_valid(png, info, PNG_INFO_tRNS) != 0;
    return true;
}

// Every colour type and depth to 8-bit RGB or RGBA; libpng applies them in its own fixed order.
void setTransforms(png_structp png, const PngHeader &header, bool alpha)
{
    if (header.colourType == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(png);
    if (header.colourType == PNG_COLOR_TYPE_GRAY && header.bitDepth < 8)
        png_set_expand_gray_1_2_4_to_8(png);
    if (header.transparency && alpha)
        png_set_tRNS_to_alpha(png);
    if (header.bitDepth == 16)
        png_set_scale_16(png); // (v * 255 + 32895) >> 16: exactly round(v / 257) for every 16-bit v
    if (!(header.colourType & PNG_COLOR_MASK_COLOR))
        png_set_gray_to_rgb(png);
    const bool hasAlpha = (header.colourType & PNG_COLOR_MASK_ALPHA) || (header.transparency && alpha);
    if (alpha && !hasAlpha)
        png_set_add_alpha(png, 0xffff, PNG_FILLER_AFTER);
    if (!alpha)
        png_set_strip_alpha(png);
    png_set_interlace_handling(png);
}

// setjmp: plain data only. The rows' size is checked before libpng writes into them.
bool readRows(png_structp png, png_infop info, const PngHeader *header, bool alpha, size_t rowBytes, png_bytepp rows)
{
    if (setjmp(png_jmpbuf(png)))
        return false;
    setTransforms(png, *header, alpha);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != rowBytes)
        png_error(png, "the decoded rows do not have the expected size");
    png_read_image(png, rows);
    png_read_end(png, nullptr);
    return true;
}

// setjmp: plain data only.
bool writeRows(png_structp png, png_infop info, png_uint_32 width, png_uint_32 height, png_bytepp rows)
{
    if (setjmp(png_jmpbuf(png)))
        return false;
    png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
                 PNG_FILTER_TYPE_BASE);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_compression_level(png, Z_BEST_SPEED);
    png_set_compression_strategy(png, Z_RLE);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, info);
    return true;
}

Error malformed(const PngIo &io)
{
    return makeError(ErrorCode::Malformed, std::string("PNG: ") + io.message);
}

Error noLibpng()
{
    return makeError(ErrorCode::Io, "PNG: libpng cannot make its structures (out of memory)");
}

} // namespace

bool isPng(std::span<const uint8_t> file)
{
    return file.size() >= 8 && png_sig_cmp(file.data(), 0, 8) == 0;
}

Result<ImageFileInfo> pngInfo(std::span<const uint8_t> file)
{
    PngIo io;
    io.data = file.data();
    io.size = file.size();
    ReadHandles handles(io);
    if (!handles.info)
        return noLibpng();
    PngHeader header;
    if (!readHeader(handles.png, handles.info, &header))
        return malformed(io);
    return ImageFileInfo{ImageFileType::Png, header.width, header.height};
}

Result<DecodedImage> decodePng(std::span<const uint8_t> file, ImageChannels channels, unsigned maxSide)
{
    PngIo io;
    io.data = file.data();
    io.size = file.size();
    ReadHandles handles(io);
    if (!handles.info)
        return noLibpng();
    PngHeader header;
    if (!readHeader(handles.png, handles.info, &header))
        return malformed(io);
    if (auto fits = checkSide({ImageFileType::Png, header.width, header.height}, maxSide); !fits)
        return fits.error();
    const size_t rowBytes = size_t(header.width) * size_t(channels);
    DecodedImage image{header.width, header.height, channels, std::vector<uint8_t>(rowBytes * header.height)};
    std::vector<png_bytep> rows(header.height);
    for (size_t y = 0; y < rows.size(); ++y)
        rows[y] = image.pixels.data() + y * rowBytes;
    if (!readRows(handles.png, handles.info, &header, channels == ImageChannels::Rgba, rowBytes, rows.data()))
        return malformed(io);
    return image;
}

} // namespace overlayd
namespace overlayd {

Result<std::vector<uint8_t>> encodePng(const RgbImage &image)
{
    if (image.rgb.size() != size_t(image.width) * image.height * 3)
        return makeError(ErrorCode::InvalidArgument, "PNG: the image's pixels do not match its size");
    std::vector<uint8_t> bytes;
    PngIo io;
    io.out = &bytes;
    WriteHandles handles(io);
    if (!handles.info)
        return noLibpng();
    // libpng only reads the rows (no write transforms are set): its API just does not say const.
    std::vector<png_bytep> rows(image.height);
    for (unsigned y = 0; y < image.height; ++y)
        rows[y] = const_cast<png_bytep>(image.row(y));
    if (!writeRows(handles.png, handles.info, image.width, image.height, rows.data()))
        return makeError(ErrorCode::Io, std::string("PNG encoding failed: ") + io.message);
    return bytes;
}

} // namespace overlayd
