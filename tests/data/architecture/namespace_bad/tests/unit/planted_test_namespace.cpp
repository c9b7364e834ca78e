// SPDX-License-Identifier: Apache-2.0
// A test's own namespace beside overlayd::test: the layering test must refuse it too.
namespace overlayd::replay {

int planted()
{
    return 0;
}

} // namespace overlayd::replay
