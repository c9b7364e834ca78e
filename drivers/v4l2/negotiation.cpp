// SPDX-License-Identifier: Apache-2.0
// Negotiation: format fallback order, nearest size, nearest rate.
#include "drivers/v4l2/negotiation.h"

#include "base/number_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "drivers/v4l2/device_format.h"

namespace overlayd {

namespace {

// Rates within this of each other are the same rate (30000/1001 answers a request for 29.97).
constexpr double kRateTolerance = 0.01;

unsigned clampToStep(unsigned value, unsigned low, unsigned high, unsigned step)
{
    value = std::clamp(value, low, high);
    step = std::max(step, 1u);
    return low + (value - low) / step * step;
}

struct Size {
    unsigned width = 0, height = 0;
};

// The size in `range` nearest to the request: exact when it fits, else the smallest area difference.
Size nearestIn(const SizeRange &range, unsigned width, unsigned height)
{
    return {clampToStep(width, range.minWidth, range.maxWidth, range.stepWidth),
            clampToStep(height, range.minHeight, range.maxHeight, range.stepHeight)};
}

double sizeCost(Size size, unsigned width, unsigned height)
{
    const double area = std::abs(double(size.width) * size.height - double(width) * height);
    return area + std::abs(double(size.width) - width) + std::abs(double(size.height) - height);
}

Size nearestSize(const OfferedFormat &offer, unsigned width, unsigned height)
{
    if (offer.sizes.empty())
        return {width, height};
    Size best{};
    double bestCost = std::numeric_limits<double>::infinity();
    for (const SizeRange &range : offer.sizes) {
        const Size candidate = nearestIn(range, width, height);
        const double cost = sizeCost(candidate, width, height);
        if (cost < bestCost) {
            best = candidate;
            bestCost = cost;
        }
    }
    return best;
}

const OfferedFormat *findOffer(std::span<const OfferedFormat> offers, uint32_t fourcc)
{
    for (const OfferedFormat &offer : offers) {
        if (fourcc != 0 && offer.fourcc == fourcc)
            return &offer;
    }
    return nullptr;
}

const OfferedFormat *findMjpeg(std::span<const OfferedFormat> offers)
{
    for (const OfferedFormat &offer : offers) {
        if (isMjpeg(offer.fourcc))
            return &offer;
    }
    return nullptr;
}

std::string describeSizes(const std::vector<SizeRange> &sizes)
{
    std::string text;
    for (const SizeRange &range : sizes) {
        text += " " + std::to_string(range.minWidth) + "x" + std::to_string(range.minHeight);
        if (range.maxWidth != range.minWidth || range.maxHeight != range.minHeight)
            text += ".." + std::to_string(range.maxWidth) + "x" + std::to_string(range.maxHeight);
    }
    return text;
}

} // namespace

FormatChoice chooseFormat(const Request &request, std::span<const OfferedFormat> offers)
{
    const uint32_t wanted = request.format ? request.format->fourcc : 0;
    const OfferedFormat *offer = findOffer(offers, wanted);
    if (!offer)
        offer = findOffer(offers, multiPlaneVariant(wanted));
    if (!offer)
        offer = findMjpeg(offers);
    if (!offer) {
        const std::string name = request.format ? std::string(request.format->name) : "?";
        return {Verdict::Invalid, 0, 0, 0, "does not offer " + name + "; it offers " + describeOffers(offers)};
    }
    const Size size = nearestSize(*offer, request.width, request.height);
    const bool exact = offer->fourcc == wanted || offer->fourcc == multiPlaneVariant(wanted);
    const bool same = exact && size.width == request.width && size.height == request.height;
    return {same ? Verdict::Valid : Verdict::Adjusted, offer->fourcc, size.width, size.height, {}};
}

double chooseRate(double wantedFps, std::span<const RateRange> rates)
{
    double best = wantedFps, bestDistance = std::numeric_limits<double>::infinity();
    for (const RateRange &range : rates) {
        const double candidate = std::clamp(wantedFps, range.minFps, range.maxFps);
        const double distance = std::abs(candidate - wantedFps);
        if (distance < bestDistance - kRateTolerance) {
            best = candidate;
            bestDistance = distance;
        }
    }
    return bestDistance <= kRateTolerance ? wantedFps : best;
}

std::string describeOffers(std::span<const OfferedFormat> offers)
{
    if (offers.empty())
        return "no formats";
    std::string text;
    for (const OfferedFormat &offer : offers) {
        if (!text.empty())
            text += ", ";
        text += fourccName(offer.fourcc) + describeSizes(offer.sizes);
    }
    return text;
}

std::string describeMode(unsigned width, unsigned height, double fps, const std::string &format)
{
    return formatted("%ux%u@%g %s", width, height, fps, format.c_str());
}

} // namespace overlayd
