// TextRenderer: OpenCV's FreeType2 (8-bit BGR targets only in OpenCV 4.6, so text is drawn white on black in a
// scratch image and one channel is kept as coverage), with the Hershey font as the fallback.
#include "overlay/raster/text_renderer.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace overlayd {

namespace {

// Hershey Simplex is 22 units tall at scale 1 (cap height about 16); this scale gives a cap height close to
// DejaVu's at the same requested size.
double hersheyScale(double sizePx)
{
    return 0.8 * sizePx / 22.0;
}

int fontHeight(double sizePx)
{
    return std::max(1, int(std::lround(sizePx)));
}

void warnOnce(const std::string &fontPath)
{
    static std::atomic<bool> warned{false};
    if (!warned.exchange(true))
        std::fprintf(stderr, "overlayd: warning: cannot load font %s; text falls back to OpenCV's Hershey font\n",
                     fontPath.c_str());
}

} // namespace

TextRenderer::TextRenderer(const std::string &fontPath)
{
    try {
        auto freeType = cv::freetype::createFreeType2();
        freeType->loadFontData(fontPath, 0);
        freeType_ = freeType;
    } catch (const cv::Exception &) {
        warnOnce(fontPath);
    }
}

TextRenderer::Box TextRenderer::measure(const std::string &text, double sizePx) const
{
    constexpr size_t kMaxCached = 64; // bounded like the coverage cache: token text makes new strings
    auto key = std::make_pair(text, sizePx);
    if (const auto it = boxes_.find(key); it != boxes_.end())
        return it->second;
    if (boxes_.size() >= kMaxCached)
        boxes_.clear();
    const Box box = measureUncached(text, sizePx);
    boxes_.emplace(std::move(key), box);
    return box;
}

TextRenderer::Box TextRenderer::measureUncached(const std::string &text, double sizePx) const
{
    int baseline = 0;
    cv::Size size;
    if (freeType_)
        size = freeType_->getTextSize(text, fontHeight(sizePx), -1, &baseline);
    else
        size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, hersheyScale(sizePx), 1, &baseline);
    // One spare pixel on each side: anti-aliased edges spill slightly outside the box OpenCV reports.
    return {size.width + 2, size.height + 1, baseline + 1};
}

cv::Mat TextRenderer::render(const std::string &text, double sizePx, bool antialias) const
{
    // Bounded: token text (a timestamp) makes a new string every second.
    constexpr size_t kMaxCached = 64;
    const auto key = std::make_tuple(text, sizePx, antialias);
    if (const auto it = cache_.find(key); it != cache_.end())
        return it->second;
    if (cache_.size() >= kMaxCached)
        cache_.clear();
    return cache_[key] = draw(text, sizePx, antialias);
}

cv::Mat TextRenderer::draw(const std::string &text, double sizePx, bool antialias) const
{
    const Box box = measure(text, sizePx);
    cv::Mat bgr = cv::Mat::zeros(std::max(box.height(), 1), std::max(box.width, 1), CV_8UC3);
    const cv::Point baselineLeft(1, box.ascent);
    const int lineType = antialias ? cv::LINE_AA : cv::LINE_8;
    if (freeType_)
        freeType_->putText(bgr, text, baselineLeft, fontHeight(sizePx), cv::Scalar::all(255), -1, lineType, true);
    else
        cv::putText(bgr, text, baselineLeft, cv::FONT_HERSHEY_SIMPLEX, hersheyScale(sizePx), cv::Scalar::all(255), 1,
                    lineType);
    cv::Mat coverage;
    cv::extractChannel(bgr, coverage, 0);
    return coverage;
}

} // namespace overlayd
