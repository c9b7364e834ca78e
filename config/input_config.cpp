// SPDX-License-Identifier: Apache-2.0
// [[input.text]]: text slots fed by files; [[input.path]]: the points of a polyline or markers annotation from a
// file; [[input.can]]: signals on a CAN bus, into the guide lines' steering or
// a text slot. A target must exist in the scene (a typo would feed nothing, silently) and is fed by one input; a
// watched file's folder must exist and the file, if there, be a regular one (the file itself may appear later: a
// program that writes it may start after the daemon). A CAN interface need not exist (like a camera it may appear
// after the daemon starts), but its name must be one the kernel could give.
#include "config/config_sections.h"

#include <algorithm>
#include <filesystem>

#include "base/utf8.h"
#include "config/limits.h"
#include "inputs/can_signal.h"
#include "inputs/can_socket.h"
#include "inputs/text_file_watch.h"
#include "overlay/shapes/scene_checks.h"
#include "overlay/shapes/text_tokens.h"

namespace overlayd {

namespace {

// The file an [[input.text]] or [[input.path]] watches: its folder must exist (the daemon watches the folder), and
// what is at the path, if anything, must be a regular file (watchedFileProblem, as the watch refuses it).
void readWatchedFile(TableReader &table, const std::string &baseDirectory, const std::string &missing, std::string &out)
{
    const std::optional<std::string> file = table.string("file");
    if (!file) {
        if (!table.has("file"))
            table.problem("file", "missing: " + missing);
        return;
    }
    if (file->empty()) {
        table.problem("file", "an empty path");
        return;
    }
    out = resolvePath(baseDirectory, *file);
    std::filesystem::path folder = std::filesystem::path(out).parent_path();
    if (folder.empty()) // a config given as a relative path in the working directory
        folder = ".";
    std::error_code error;
    if (!std::filesystem::is_directory(folder, error))
        table.problem("file", "the folder " + folder.string() +
                                  " does not exist (the file may appear later; its folder must be there)");
    else if (const std::string problem = watchedFileProblem(out); !problem.empty())
        table.problem("file", problem);
}

void readTextInput(TableReader &table, const std::string &baseDirectory, const std::vector<std::string> &slots,
                   std::vector<std::string> &fed, TextInputOptions &out)
{
    if (auto slot = table.string("slot")) {
        out.slot = *slot;
        if (std::find(slots.begin(), slots.end(), *slot) == slots.end()) {
            std::string message = "no text annotation shows {slot:" + *slot + "}";
            if (const std::string guess = closestMatch(*slot, slots); !guess.empty())
                message += "; did you mean '" + guess + "'?";
            table.problem("slot", std::move(message));
        } else if (std::find(fed.begin(), fed.end(), *slot) != fed.end()) {
            table.problem("slot", "slot '" + *slot + "' is already fed by another [[input.text]]");
        }
        fed.push_back(*slot);
    } else if (!table.has("slot")) {
        table.problem("slot", "missing: the {slot:NAME} this file feeds");
    }
    readWatchedFile(table, baseDirectory, "the file another program writes", out.file);
    if (auto bytes = table.integer("max_bytes", 1, int64_t(kMaxInputTextBytes)))
        out.maxBytes = size_t(*bytes);
    table.finish();
}

void readPathInput(TableReader &table, const std::string &baseDirectory, const OverlayScene &scene,
                   std::vector<std::string> &fed, PathInputOptions &out)
{
    if (auto name = table.string("annotation")) {
        out.annotation = *name;
        const auto found = std::find_if(scene.annotations.begin(), scene.annotations.end(),
                                        [&](const Annotation &a) { return a.name == *name; });
        std::vector<std::string> candidates;
        for (const Annotation &a : scene.annotations)
            if (std::holds_alternative<PolylineShape>(a.shape) || std::holds_alternative<MarkersShape>(a.shape))
                candidates.push_back(a.name);
        if (found == scene.annotations.end() ||
            std::find(candidates.begin(), candidates.end(), *name) == candidates.end()) {
            std::string message = "no polyline or markers annotation is named '" + *name + "'";
            if (const std::string guess = closestMatch(*name, candidates); !guess.empty())
                message += "; did you mean '" + guess + "'?";
            table.problem("annotation", std::move(message));
        } else if (std::find(fed.begin(), fed.end(), *name) != fed.end()) {
            table.problem("annotation", "'" + *name + "' is already fed by another [[input.path]]");
        }
        fed.push_back(*name);
    } else if (!table.has("annotation")) {
        table.problem("annotation", "missing: the polyline or markers annotation whose points the file holds");
    }
    readWatchedFile(table, baseDirectory, "the file another program writes (one \"x y z\" per line)", out.file);
    table.finish();
}

// "ANNOTATION.steering" or "slot:NAME".
void readCanTarget(TableReader &table, const OverlayScene &scene, const std::vector<std::string> &slots,
                   std::vector<std::string> &fed, CanTarget &out)
{
    const std::optional<std::string> target = table.string("target");
    if (!target) {
        if (!table.has("target"))
            table.problem("target", "missing: \"GUIDE-LINES NAME.steering\" or \"slot:NAME\"");
        return;
    }
    if (target->starts_with("slot:")) {
        out = {CanTarget::Kind::Slot, target->substr(5)};
        if (std::find(slots.begin(), slots.end(), out.name) == slots.end())
            table.problem("target", "no text annotation shows {slot:" + out.name + "}");
    } else if (target->ends_with(".steering")) {
        out = {CanTarget::Kind::Steering, target->substr(0, target->size() - 9)};
        const auto annotation = std::find_if(scene.annotations.begin(), scene.annotations.end(),
                                             [&](const Annotation &a) { return a.name == out.name; });
        if (annotation == scene.annotations.end() || !std::holds_alternative<GuideLinesShape>(annotation->shape))
            table.problem("target", "no guide-lines annotation is named '" + out.name + "'");
    } else {
        table.problem("target", "expected \"GUIDE-LINES NAME.steering\" or \"slot:NAME\", got \"" + *target + "\"");
        return;
    }
    const std::string key = (out.kind == CanTarget::Kind::Slot ? "slot:" : "steering:") + out.name;
    if (std::find(fed.begin(), fed.end(), key) != fed.end())
        table.problem("target", "'" + *target + "' is already fed by another input");
    fed.push_back(key);
}

// What a slot target shows must be text a slot takes (checkSlotText, as SceneControl refuses it): the stale text,
// and the unit after the shortest reading of [min, max] (a unit that does not fit then never shows). min >= max is
// refused at max already.
void checkSlotTexts(TableReader &table, const CanInputOptions &in)
{
    if (Status stale = checkSlotText(in.staleText); !stale)
        table.problem("stale_text", "it could never show: " + stale.error().message);
    if (in.target.kind != CanTarget::Kind::Slot || in.min >= in.max) // a steering target shows no unit
        return;
    const std::string shortest = canReadingText(std::clamp(0.0, in.min, in.max), in.decimals, in.unit);
    if (Status unit = checkSlotText(shortest); !unit)
        table.problem("unit", "no reading could show: " + unit.error().message);
}

void readCanInput(TableReader &table, const OverlayScene &scene, const std::vector<std::string> &slots,
                  std::vector<std::string> &fed, CanInputOptions &out)
{
    out.name = table.string("name").value_or("");
    if (auto interface = table.string("interface")) {
        out.interface = *interface;
        if (const std::string problem = canInterfaceProblem(*interface); !problem.empty())
            table.problem("interface", problem); // what opening the socket would refuse
    } else if (!table.has("interface")) {
        table.problem("interface", "missing: the SocketCAN interface (e.g. can0)");
    }
    out.id.extended = table.boolean("id_extended").value_or(false);
    const int64_t maxId = out.id.extended ? kMaxExtendedCanId : kMaxStandardCanId;
    if (auto id = table.integer("id", 0, maxId))
        out.id.id = uint32_t(*id);
    else if (!table.has("id"))
        table.problem("id", "missing: the frame's CAN id (0..0x7FF, or up to 0x1FFFFFFF with id_extended = true)");
    CanSignalLayout &layout = out.layout;
    const bool haveStart = table.has("start_bit") && table.has("length");
    layout.startBit = unsigned(table.integer("start_bit", 0, 63).value_or(0));
    layout.length = unsigned(table.integer("length", 1, 64).value_or(8));
    if (!haveStart)
        table.problem(table.has("start_bit") ? "length" : "start_bit", "missing: the signal's start_bit and length");
    using Order = std::pair<std::string_view, bool>;
    layout.bigEndian =
        table.choice<bool>("byte_order", {Order{"little-endian", false}, Order{"big-endian", true}}).value_or(false);
    layout.isSigned = table.boolean("signed").value_or(false);
    layout.scale = table.number("scale", -kMaxCanValue, kMaxCanValue).value_or(1.0);
    if (layout.scale == 0.0)
        table.problem("scale", "a scale of 0 makes every value the offset");
    layout.offset = table.number("offset", -kMaxCanValue, kMaxCanValue).value_or(0.0);
    if (haveStart)
        if (const std::string problem = canLayoutProblem(layout); !problem.empty())
            table.problem("start_bit", problem);
    out.unit = table.string("unit").value_or("");
    if (const auto problem = outsideTextProblem(out.unit))
        table.problem("unit", *problem + " (the unit is shown on one line)");
    out.min = table.number("min", -kMaxCanValue, kMaxCanValue).value_or(out.min);
    out.max = table.number("max", -kMaxCanValue, kMaxCanValue).value_or(out.max);
    if (out.min >= out.max)
        table.problem("max", "max must be greater than min");
    out.timeoutMs = int(table.integer("timeout_ms", 1, kMaxCanTimeoutMs).value_or(out.timeoutMs));
    out.step = table.number("step", 0.0, kMaxCanValue).value_or(out.step);
    out.decimals = int(table.integer("decimals", 0, 9).value_or(out.decimals));
    out.staleText = table.string("stale_text").value_or(out.staleText);
    readCanTarget(table, scene, slots, fed, out.target);
    checkSlotTexts(table, out);
    if (out.name.empty())
        out.name = out.interface + ":" + std::to_string(out.id.id);
    table.finish();
}

} // namespace

void readInputs(TableReader &root, const std::string &baseDirectory, const OverlayScene &scene, InputOptions &out)
{
    auto input = root.table("input");
    if (!input)
        return;
    const std::vector<std::string> slots = textSlotNames(scene);
    std::vector<std::string> fed;
    std::vector<TableReader> texts = input->tables("text", kMaxTextInputs);
    for (size_t i = 0; i < texts.size(); ++i)
        readTextInput(texts[i], baseDirectory, slots, fed, out.text.emplace_back());
    std::vector<TableReader> paths = input->tables("path", kMaxPathInputs);
    std::vector<std::string> fedPaths;
    for (size_t i = 0; i < paths.size(); ++i)
        readPathInput(paths[i], baseDirectory, scene, fedPaths, out.paths.emplace_back());
    std::vector<std::string> fedByCan;
    for (const std::string &slot : fed)
        fedByCan.push_back("slot:" + slot);
    std::vector<TableReader> cans = input->tables("can", kMaxCanInputs);
    for (size_t i = 0; i < cans.size(); ++i)
        readCanInput(cans[i], scene, slots, fedByCan, out.can.emplace_back());
    input->finish();
}

} // namespace overlayd
