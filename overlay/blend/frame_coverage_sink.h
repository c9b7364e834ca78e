// SPDX-License-Identifier: Apache-2.0
// FrameCoverageSink: blends coverage straight into a frame in its own pixel format -- the moving-camera path, with
// no RGBA layer and no per-frame layer conversion. Chroma-aware like NativeLayer: a subsampled chroma sample takes
// the coverage-weighted colour of its macropixel.
#pragma once

#include <cstdint>
#include <vector>

#include "media/colorimetry.h"
#include "media/frame.h"
#include "overlay/blend/ycbcr.h"
#include "overlay/raster/coverage_sink.h"

namespace overlayd {

class FrameCoverageSink final : public CoverageSink
{
public:
    FrameCoverageSink(const PixelFormatInfo &format, Colorimetry colorimetry);

    // The frame painted from now on; the caller has checked it (checkFrame, format and size). Sink pixel (x, y) is
    // frame pixel (x, y).
    void setFrame(const FrameView &frame);

    void begin(Rgba colour) override;
    void row(int y, int x0, const uint8_t *coverage, int count) override;
    void rowRuns(int y, const CoverageRun *runs, size_t count) override;
    void end() override;

private:
    // Chroma groups [g0, g1) of a chroma row.
    struct Interval {
        unsigned g0 = 0, g1 = 0;
    };

    static constexpr unsigned kNoPairs = ~0u;

    // Where a format keeps its samples, read once from the pixel-format table.
    struct Layout {
        bool rgb = false, chroma = false;
        bool packed422 = false; // YUYV, UYVY, YVYU: a macropixel's luma and chroma in four consecutive bytes
        unsigned lumaStep = 1, lumaOffset = 0; // luma byte of pixel x: x * lumaStep + lumaOffset (plane 0)
        bool byteLuma = false;                 // YUV with one-byte luma samples side by side (planar, NV12, GREY)
        unsigned chromaStep = 0;               // bytes between chroma groups in the Cb/Cr plane(s)
        unsigned cbPlane = 0, crPlane = 0, cbOffset = 0, crOffset = 0;
        unsigned vSub = 1;              // luma rows per chroma row
        unsigned pairOffset = kNoPairs; // NV12/NV21/NV16: offset of a group's first chroma byte (Cb, Cr side by side)
        unsigned pixelBytes = 0;        // RGB: bytes per pixel
    };

    // The item's colour at full opacity, per touched byte kind; opacity scales it (premultiplied Y'CbCr and RGB
    // are linear in alpha for a fixed colour).
    struct ItemColour {
        unsigned luma = 0, cb = 0, cr = 0;
        unsigned pairCodes[2] = {};    // codes of a macropixel's first and second chroma byte (by offset)
        uint16_t packedChroma[8] = {}; // pairCodes four times, as the packed 4:2:2 kernel's chroma lanes
        uint8_t rgb[4] = {};           // per byte of an RGB pixel; an alpha byte composes "over" as 255
        uint8_t rgbMask[4] = {};       // 0xff for a byte the blend writes, 0 for an X byte
        uint8_t alpha = 255;
    };

    static Layout layoutOf(const PixelFormatInfo &format);
    // Writes a row() call's opacities with pixel x0's at alpha, 0 before it and in the 16 bytes after the last: the
    // kernels read whole vectors and whole macropixels, and a zero opacity leaves a byte as it is.
    void stage(const uint8_t *coverage, unsigned count, uint8_t *alpha) const;
    // row() and rowRuns(): the row's address and the format's path found once; readAhead says the runs' coverage
    // may be read kCoverageReadAhead bytes past their ends (rowRuns), so short runs skip the staging.
    void blendRuns(int y, const CoverageRun *runs, size_t count, bool readAhead);
    // A thin line's run (its pixels and the one before an odd x0 within eight) from its coverage array, unstaged,
    // in packed 4:2:2 or in a format with one-byte luma: false, having done nothing, for any other run.
    bool blendShortPacked(uint8_t *row, const CoverageRun &run) const;
    bool blendShortYuv(uint8_t *row, int y, const CoverageRun &run);
    void blendPackedRow(uint8_t *row, int y, int x0, const uint8_t *alpha, int count);
    void blendYuvRow(uint8_t *row, int y, int x0, const uint8_t *alpha, int count);
    // A luma row's run of chroma groups, after its opacities were added to alphaSums_: blended now if the chroma
    // row is complete with this luma row, else left to wait for the next.
    void addChromaGroups(int y, int chromaRow, Interval groups);
    // The chroma row of luma row y, with the previous one flushed if it was left pending.
    int enterChromaRow(int y);
    void flushChroma();
    void blendLastRowGroups(unsigned chromaRow, Interval groups);
    // Groups [g0, g1) of a chroma row blended with their opacity sums, which are zeroed: NV12/NV21's few groups in
    // one inline step, any other interval by blendChromaRange.
    void blendChromaInterval(unsigned chromaRow, Interval interval);
    void blendChromaRange(unsigned chromaRow, Interval interval);
    // The bits by which a chroma row's opacity sums scale to four pixels' worth (2 - its luma rows).
    unsigned chromaShift(unsigned chromaRow) const;
    // NV12/NV21/NV16: the first Cb/Cr pair of a chroma row.
    uint8_t *pairRow(unsigned chromaRow) const;

    // The pixel loops, in 16-bit vector lanes.
    // pixels: the first byte of pixel x0's bytes; room: visible bytes of the row from there (a short run is one
    // 16-byte vector operation when they suffice); alpha is staged.
    static void blendLuma(uint8_t *pixels, const Layout &layout, const uint8_t *alpha, unsigned count, unsigned value,
                          size_t room);
    static void blendRgb(uint8_t *dst, unsigned pixelBytes, const uint8_t *alpha, unsigned count,
                         const ItemColour &colour);
    // alpha is staged (see stage()); sums has eight groups of slack past the last.
    static void accumulateAlpha(uint16_t *sums, unsigned x0, const uint8_t *alpha, unsigned count);
    // count groups from cb/cr, Cb and Cr samples `step` bytes apart (planar and packed chroma).
    static void blendChroma(uint8_t *cb, uint8_t *cr, unsigned step, uint16_t *sums, unsigned count, unsigned shift,
                            const ItemColour &colour);

    const PixelFormatInfo *format_;
    Colorimetry colorimetry_;
    FrameView frame_{};
    size_t rowBytes_ = 0; // visible bytes of a plane-0 row
    YcbcrEncoder encoder_;
    Layout layout_;
    ItemColour colour_;

    // Scratch grown by setFrame and then reused: no allocation per frame.
    std::vector<uint8_t> alpha_;      // opacities of one row() call, staged (see stage())
    std::vector<uint16_t> alphaSums_; // per chroma group of the pending chroma row; all zero between flushes
    std::vector<Interval> intervals_; // groups of pendingChromaRow_ touched by its first luma row
    size_t nextInterval_ = 0;         // the first of them not blended yet
    int pendingChromaRow_ = -1;
};

} // namespace overlayd
