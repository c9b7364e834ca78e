// Text coverage: DejaVu Sans through OpenCV's FreeType module, or OpenCV's Hershey font when the font is missing.
#pragma once

#include <map>
#include <string>
#include <tuple>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/freetype.hpp>

namespace overlayd {

inline constexpr const char *kDefaultFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

class TextRenderer
{
public:
    // Falls back to the Hershey font, with a warning on stderr (once per process), when fontPath cannot be loaded.
    explicit TextRenderer(const std::string &fontPath = kDefaultFontPath);

    // The text's box: width, and height split at the baseline into ascent and descent.
    struct Box {
        int width = 0, ascent = 0, descent = 0;
        int height() const { return ascent + descent; }
    };
    // Cached like render(): a label's box is asked for every frame while the camera moves.
    Box measure(const std::string &text, double sizePx) const;
    // The coverage (0..255) of the text drawn in its box, CV_8UC1 of the box's size. Cached: labels keep their text
    // while the camera moves, and FreeType's rendering is the slow part of a redraw. Read-only.
    cv::Mat render(const std::string &text, double sizePx, bool antialias) const;

    bool usesFreeType() const { return !freeType_.empty(); }

private:
    cv::Mat draw(const std::string &text, double sizePx, bool antialias) const;

    cv::Ptr<cv::freetype::FreeType2> freeType_;
    Box measureUncached(const std::string &text, double sizePx) const;

    mutable std::map<std::tuple<std::string, double, bool>, cv::Mat> cache_;
    mutable std::map<std::pair<std::string, double>, Box> boxes_;
};

} // namespace overlayd
