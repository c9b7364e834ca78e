// SPDX-License-Identifier: Apache-2.0
// The LineProvider of an overlayd built without libgpiod: every request is refused, saying so.
#include "gpio/line_provider.h"

namespace overlayd {

namespace {

constexpr const char *kWithout = "this overlayd was built without libgpiod (install libgpiod-dev and rebuild)";

class NoProvider final : public LineProvider
{
public:
    Result<std::unique_ptr<InputLine>> requestInput(const InputRequest &, const std::string &) override
    {
        return makeError(ErrorCode::Unsupported, kWithout);
    }
    Result<std::unique_ptr<OutputLine>> requestOutput(const OutputRequest &, const std::string &) override
    {
        return makeError(ErrorCode::Unsupported, kWithout);
    }
};

} // namespace

std::unique_ptr<LineProvider> makeLineProvider()
{
    return std::make_unique<NoProvider>();
}

bool haveLibgpiod()
{
    return false;
}

Result<std::vector<ChipInfo>> listChips()
{
    return makeError(ErrorCode::Unsupported, kWithout);
}

} // namespace overlayd
