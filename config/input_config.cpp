// [[input.text]]: text slots fed by files. The slot must be shown by some text annotation (a typo would feed
// nothing, silently), one slot is fed by one input, and the file's folder must exist (the file itself may appear
// later: a program that writes it may start after the daemon).
#include "config/config_sections.h"

#include <algorithm>
#include <filesystem>

#include "overlay/shapes/scene_checks.h"

namespace overlayd::config {

namespace {

void readTextInput(TableReader &table, const std::string &baseDirectory, const std::vector<std::string> &slots,
                   std::vector<std::string> &fed, inputs::TextInputOptions &out)
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
    if (auto file = table.string("file"); file && !file->empty()) {
        out.file = resolvePath(baseDirectory, *file);
        const std::filesystem::path folder = std::filesystem::path(out.file).parent_path();
        std::error_code error;
        if (!std::filesystem::is_directory(folder, error))
            table.problem("file", "the folder " + folder.string() +
                                      " does not exist (the file may appear later; "
                                      "its folder must be there)");
    } else if (!file) {
        table.problem("file", "missing: the file another program writes");
    } else {
        table.problem("file", "an empty path");
    }
    if (auto bytes = table.integer("max_bytes", 1, int64_t(inputs::kMaxTextBytes)))
        out.maxBytes = size_t(*bytes);
    table.finish();
}

} // namespace

void readInputs(TableReader &root, const std::string &baseDirectory, const OverlayScene &scene,
                inputs::InputOptions &out)
{
    auto input = root.table("input");
    if (!input)
        return;
    const std::vector<std::string> slots = textSlotNames(scene);
    std::vector<std::string> fed;
    std::vector<TableReader> texts = input->tables("text");
    if (texts.size() > inputs::kMaxTextInputs)
        input->problem("text", "at most " + std::to_string(inputs::kMaxTextInputs) + " text inputs");
    for (size_t i = 0; i < texts.size() && i < inputs::kMaxTextInputs; ++i)
        readTextInput(texts[i], baseDirectory, slots, fed, out.text.emplace_back());
    input->finish();
}

} // namespace overlayd::config
