// SPDX-License-Identifier: Apache-2.0
// FakeGpio's provider and lines.
#include "fake_gpio.h"

namespace overlayd::test {

namespace {

std::string nameOf(const LineAddress &address)
{
    return address.name.empty() ? std::to_string(address.offset) : address.name;
}

Error lostError()
{
    return makeError(ErrorCode::DeviceLost, "No such device");
}

class FakeInput final : public InputLine
{
public:
    explicit FakeInput(FakeGpio::Line &line) : line_(line) {}
    ~FakeInput() override { line_.consumer.clear(); }
    int fd() const override { return line_.events.get(); }
    Result<unsigned> drainEvents() override
    {
        if (line_.lost)
            return lostError();
        uint64_t count = 0;
        return ::read(line_.events.get(), &count, sizeof(count)) == sizeof(count) ? unsigned(count) : 0u;
    }
    Result<bool> active() override
    {
        if (line_.lost)
            return lostError();
        return line_.physical != line_.activeLow;
    }

private:
    FakeGpio::Line &line_;
};

class FakeOutput final : public OutputLine
{
public:
    explicit FakeOutput(FakeGpio::Line &line) : line_(line) {}
    // Released: the line floats back to its inactive level, as gpio-sim's pull does with no bias.
    ~FakeOutput() override { line_.consumer.clear(); }
    Status setActive(bool active) override
    {
        if (line_.lost)
            return lostError();
        line_.physical = active != line_.activeLow;
        return Ok{};
    }

private:
    FakeGpio::Line &line_;
};

class FakeProvider final : public LineProvider
{
public:
    explicit FakeProvider(FakeGpio &gpio) : gpio_(gpio) {}

    Result<std::unique_ptr<InputLine>> requestInput(const InputRequest &request, const std::string &consumer) override
    {
        auto line = claim(request.line, consumer);
        if (!line)
            return line.error();
        (*line)->activeLow = request.activeLow;
        (*line)->bias = request.bias;
        return std::unique_ptr<InputLine>(std::make_unique<FakeInput>(**line));
    }
    Result<std::unique_ptr<OutputLine>> requestOutput(const OutputRequest &request,
                                                      const std::string &consumer) override
    {
        auto line = claim(request.line, consumer);
        if (!line)
            return line.error();
        (*line)->activeLow = request.activeLow;
        (*line)->physical = request.active != request.activeLow;
        return std::unique_ptr<OutputLine>(std::make_unique<FakeOutput>(**line));
    }

private:
    Result<FakeGpio::Line *> claim(const LineAddress &address, const std::string &consumer)
    {
        if (address.chip == gpio_.missingChip)
            return makeError(ErrorCode::NotFound, "GPIO chip '" + address.chip + "' not found");
        FakeGpio::Line &line = gpio_.line(address.chip, nameOf(address));
        if (line.lost)
            return lostError();
        if (!line.consumer.empty())
            return makeError(ErrorCode::Io, address.describe() + " is held by '" + line.consumer + "'");
        line.consumer = consumer;
        ++line.requests;
        return &line;
    }

    FakeGpio &gpio_;
};

} // namespace

std::unique_ptr<LineProvider> FakeGpio::provider()
{
    return std::make_unique<FakeProvider>(*this);
}

} // namespace overlayd::test
