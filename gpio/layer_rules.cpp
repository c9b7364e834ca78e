// SPDX-License-Identifier: Apache-2.0
// layerVisibility: the show/hide precedence of layer_rules.h.
#include "gpio/layer_rules.h"

#include <algorithm>

namespace overlayd {

namespace {

struct Votes {
    bool hiddenByActive = false, shownByAny = false, shownByActive = false;
};

} // namespace

std::map<std::string, bool> layerVisibility(const std::vector<GpioInputOptions> &inputs,
                                            const std::vector<bool> &active)
{
    std::map<std::string, Votes> votes;
    for (size_t i = 0; i < inputs.size(); ++i) {
        const bool on = i < active.size() && active[i];
        for (const std::string &layer : inputs[i].hideLayers)
            votes[layer].hiddenByActive |= on;
        for (const std::string &layer : inputs[i].showLayers) {
            Votes &v = votes[layer];
            v.shownByAny = true;
            v.shownByActive |= on;
        }
    }
    std::map<std::string, bool> visible;
    for (const auto &[layer, v] : votes)
        visible[layer] = !v.hiddenByActive && (!v.shownByAny || v.shownByActive);
    return visible;
}

} // namespace overlayd
