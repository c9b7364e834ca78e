// What [[input.text]] asks for: live data from outside the config file, into the running scene's text slots.
// Compared whole (defaulted ==), so that a reload re-opens exactly the inputs that changed.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace overlayd::inputs {

inline constexpr size_t kMaxTextInputs = 32;
inline constexpr size_t kMaxTextBytes = 256; // a slot's limit (overlay/shapes/text_tokens.h kMaxSlotTextBytes)

// A text slot fed by a file another program writes: its first line, on the next frame after each change.
struct TextInputOptions {
    std::string slot; // a {slot:NAME} some text annotation shows
    std::string file; // absolute (resolved against the config's folder)
    size_t maxBytes = kMaxTextBytes;
    bool operator==(const TextInputOptions &) const = default;
};

struct InputOptions {
    std::vector<TextInputOptions> text;
    bool empty() const { return text.empty(); }
    bool operator==(const InputOptions &) const = default;
};

} // namespace overlayd::inputs
