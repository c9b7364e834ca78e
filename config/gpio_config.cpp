// SPDX-License-Identifier: Apache-2.0
// [[gpio.input]] and [[gpio.output]]: lines checked for shape here (chips and lines themselves only exist on the
// running machine), layers against the scene's, and no line named twice.
#include "config/config_sections.h"

#include <algorithm>

#include "gpio/line_provider.h"

namespace overlayd {

namespace {

constexpr int64_t kMaxLineOffset = 65535; // the GPIO uAPI's line offsets are u32; no chip has more

void readLine(TableReader &table, LineAddress &out)
{
    if (auto chip = table.string("chip"); chip && !chip->empty())
        out.chip = *chip;
    else if (chip || !table.has("chip"))
        table.problem("chip", "missing: the chip's name (gpiochip0), label or /dev path (see overlayd list-gpio)");
    const toml::node *line = table.node("line");
    if (!line) {
        table.problem("line", "missing: the line's offset on the chip, or its name");
    } else if (line->is_string()) {
        out.name = *line->value<std::string>();
        if (out.name.empty())
            table.problem("line", "an empty line name");
    } else if (auto offset = table.integer("line", 0, kMaxLineOffset)) {
        out.offset = unsigned(*offset);
    }
}

// Every layer named must be drawn by some annotation (a typo would otherwise switch nothing, silently).
void checkLayers(TableReader &table, std::string_view key, const std::vector<std::string> &layers,
                 const std::vector<std::string> &known)
{
    for (const std::string &layer : layers) {
        if (std::find(known.begin(), known.end(), layer) != known.end())
            continue;
        std::string list;
        for (const std::string &name : known)
            list += (list.empty() ? "" : ", ") + name;
        std::string message = "no annotation draws in layer '" + layer + "' (layers: " + list + ")";
        if (const std::string guess = closestMatch(layer, known); !guess.empty())
            message += "; did you mean '" + guess + "'?";
        table.problem(key, std::move(message));
    }
}

// A privacy mask cannot be hidden: an input whose layer holds one is refused, shown or hidden alike (an input that
// shows a layer hides it while the line is inactive).
void checkMaskLayers(TableReader &table, std::string_view key, const std::vector<std::string> &layers,
                     const std::vector<Annotation> &annotations)
{
    for (const std::string &layer : layers)
        for (const Annotation &annotation : annotations)
            if (isMask(annotation) && annotation.style.layer == layer) {
                table.problem(key, "layer '" + layer + "' holds the privacy mask '" + annotation.name +
                                       "', which nothing may hide (give the mask a layer of its own)");
                break;
            }
}

// An input must switch something, and no layer both ways: shown only while the line is active and hidden while it
// is, the layer could never be seen (layer_rules.h), whatever the line does.
void checkSwitches(TableReader &input, const GpioInputOptions &in)
{
    if (in.showLayers.empty() && in.hideLayers.empty()) {
        const char *given = input.has("show_layers") ? "show_layers" : input.has("hide_layers") ? "hide_layers" : "";
        if (*given)
            input.problem(given, "an empty list: the input would switch nothing (name the layers it shows or hides)");
        else
            input.problemAtTable("an input needs show_layers or hide_layers: the layers it switches");
        return;
    }
    for (const std::string &layer : in.hideLayers)
        if (std::find(in.showLayers.begin(), in.showLayers.end(), layer) != in.showLayers.end()) {
            input.problem("hide_layers",
                          "layer '" + layer + "' is in show_layers too: one input cannot both show and hide it");
            return;
        }
}

struct Claim {
    LineAddress line;
    std::string who;
};

// Two inputs or outputs on one line: the second is refused where it is written.
void claimLine(TableReader &table, const LineAddress &line, const std::string &who, std::vector<Claim> &claims)
{
    if (line.chip.empty())
        return;
    for (const Claim &claim : claims)
        if (claim.line.sameLine(line)) {
            table.problem("line", line.describe() + " is already used by " + claim.who +
                                      (claim.line.chip == line.chip ? "" : " (as " + claim.line.describe() + ")"));
            return;
        }
    claims.push_back({line, who});
}

void readInput(TableReader &input, size_t index, const std::vector<Annotation> &annotations,
               const std::vector<std::string> &layers, std::vector<Claim> &claims, GpioInputOptions &out)
{
    out.name = input.string("name").value_or("gpio.input[" + std::to_string(index) + "]");
    readLine(input, out.line);
    if (auto low = input.boolean("active_low"))
        out.activeLow = *low;
    if (auto bias = input.choice<Bias>("bias", {{"as-is", Bias::AsIs},
                                                {"disable", Bias::Disable},
                                                {"pull-up", Bias::PullUp},
                                                {"pull-down", Bias::PullDown}}))
        out.bias = *bias;
    if (auto debounce = input.integer("debounce_ms", 0, kMaxDebounceMs))
        out.debounceMs = unsigned(*debounce);
    if (auto show = input.strings("show_layers", kMaxLayersPerInput)) {
        out.showLayers = *show;
        checkLayers(input, "show_layers", out.showLayers, layers);
        checkMaskLayers(input, "show_layers", out.showLayers, annotations);
    }
    if (auto hide = input.strings("hide_layers", kMaxLayersPerInput)) {
        out.hideLayers = *hide;
        checkLayers(input, "hide_layers", out.hideLayers, layers);
        checkMaskLayers(input, "hide_layers", out.hideLayers, annotations);
    }
    checkSwitches(input, out);
    claimLine(input, out.line, "input '" + out.name + "'", claims);
    input.finish();
}

void readOutput(TableReader &output, size_t index, std::vector<Claim> &claims, OutputOptions &out)
{
    out.name = output.string("name").value_or("gpio.output[" + std::to_string(index) + "]");
    readLine(output, out.line);
    if (auto signal = output.choice<OutputSignal>("signal", {{"streaming", OutputSignal::Streaming},
                                                             {"no-signal", OutputSignal::NoSignal},
                                                             {"error", OutputSignal::Error},
                                                             {"frame-toggle", OutputSignal::FrameToggle}}))
        out.signal = *signal;
    if (auto low = output.boolean("active_low"))
        out.activeLow = *low;
    claimLine(output, out.line, "output '" + out.name + "'", claims);
    output.finish();
}

} // namespace

void readGpio(TableReader &root, const std::vector<Annotation> &annotations, GpioOptions &out)
{
    auto gpio = root.table("gpio");
    if (!gpio)
        return;
    if (!haveLibgpiod()) { // refused here, so that check-config refuses what run could not do
        root.problem("gpio", "this overlayd was built without GPIO lines (CMake option OVERLAYD_GPIOD, libgpiod): "
                             "[gpio] is not available");
        return;
    }
    std::vector<std::string> layers;
    for (const Annotation &annotation : annotations)
        if (std::find(layers.begin(), layers.end(), annotation.style.layer) == layers.end())
            layers.push_back(annotation.style.layer);
    std::vector<Claim> claims;
    std::vector<TableReader> inputs = gpio->tables("input", kMaxInputs);
    std::vector<TableReader> outputs = gpio->tables("output", kMaxOutputs);
    for (size_t i = 0; i < inputs.size(); ++i)
        readInput(inputs[i], i, annotations, layers, claims, out.inputs.emplace_back());
    for (size_t i = 0; i < outputs.size(); ++i)
        readOutput(outputs[i], i, claims, out.outputs.emplace_back());
    gpio->finish();
}

} // namespace overlayd
