// SPDX-License-Identifier: Apache-2.0
// Which layers the GPIO inputs decide, and how, given which inputs are active. The precedence, for a layer named by
// several inputs: hidden while any active input hides it; otherwise, if some inputs show it, visible exactly while at
// least one of those is active; otherwise (only hiding inputs, none active) visible.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "gpio/gpio_options.h"

namespace overlayd {

// Every layer some input names, with its visibility; `active[i]` is input i's settled state.
std::map<std::string, bool> layerVisibility(const std::vector<GpioInputOptions> &inputs,
                                            const std::vector<bool> &active);

} // namespace overlayd
