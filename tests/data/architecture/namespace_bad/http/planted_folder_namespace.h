// SPDX-License-Identifier: Apache-2.0
// A folder namespace where overlayd's code has one namespace: the layering test must refuse it.
#pragma once

namespace overlayd::http {

struct Planted {};

} // namespace overlayd::http
