// SPDX-License-Identifier: Apache-2.0
// The LineProvider over libgpiod 1.6 (the v1 API Debian 12 ships): every libgpiod call overlayd makes is in this
// file; a v2 backend (Debian 13) is one more file beside it.
#include <gpiod.h>

#include <cerrno>
#include <cstring>
#include <ctime>

#include "gpio/line_provider.h"

namespace overlayd {

namespace {

constexpr size_t kMaxLinesListed = 64; // in an error message

struct ChipCloser {
    void operator()(gpiod_chip *chip) const { gpiod_chip_close(chip); }
};
using ChipHandle = std::unique_ptr<gpiod_chip, ChipCloser>;

std::string errnoText()
{
    return std::strerror(errno);
}

std::string chipList()
{
    std::string list;
    gpiod_chip_iter *iter = gpiod_chip_iter_new();
    if (!iter)
        return "none";
    gpiod_chip *chip;
    gpiod_foreach_chip(iter, chip)
    {
        list += (list.empty() ? "" : ", ") + std::string(gpiod_chip_name(chip)) + " '" + gpiod_chip_label(chip) +
                "' (" + std::to_string(gpiod_chip_num_lines(chip)) + " lines)";
    }
    gpiod_chip_iter_free(iter);
    return list.empty() ? "none" : list;
}

std::string lineList(gpiod_chip *chip)
{
    std::string list;
    const unsigned count = gpiod_chip_num_lines(chip);
    for (unsigned offset = 0; offset < count && offset < kMaxLinesListed; ++offset) {
        gpiod_line *line = gpiod_chip_get_line(chip, offset);
        const char *name = line ? gpiod_line_name(line) : nullptr;
        list += (offset ? ", " : "") + std::to_string(offset) + (name ? " '" + std::string(name) + "'" : "");
    }
    if (count > kMaxLinesListed)
        list += ", ... (" + std::to_string(count) + " in all)";
    return list;
}

// The chip opened and the line found on it, or why not.
Result<std::pair<ChipHandle, gpiod_line *>> findLine(const LineAddress &address)
{
    ChipHandle chip(gpiod_chip_open_lookup(address.chip.c_str()));
    if (!chip)
        return makeError(ErrorCode::NotFound,
                         "GPIO chip '" + address.chip + "' not found (" + errnoText() + "; chips: " + chipList() + ")");
    gpiod_line *line = address.name.empty() ? gpiod_chip_get_line(chip.get(), address.offset)
                                            : gpiod_chip_find_line(chip.get(), address.name.c_str());
    if (!line)
        return makeError(ErrorCode::NotFound, address.describe() + ": no such line (" + gpiod_chip_name(chip.get()) +
                                                  " has: " + lineList(chip.get()) + ")");
    return std::pair{std::move(chip), line};
}

Status request(gpiod_line *line, const LineAddress &address, const gpiod_line_request_config &config, int value)
{
    if (gpiod_line_is_used(line) && !gpiod_line_is_requested(line)) {
        const char *consumer = gpiod_line_consumer(line);
        return makeError(ErrorCode::Io,
                         address.describe() + " is held by '" + (consumer ? consumer : "the kernel") + "'");
    }
    if (gpiod_line_request(line, &config, value) != 0) {
        const std::string why = errnoText();
        (void)gpiod_line_update(line);
        const char *consumer = gpiod_line_consumer(line);
        return makeError(ErrorCode::Io, address.describe() + ": cannot request it (" + why + ")" +
                                            (consumer ? std::string("; held by '") + consumer + "'" : ""));
    }
    return Ok{};
}

int biasFlags(Bias bias)
{
    switch (bias) {
    case Bias::AsIs:
        return 0;
    case Bias::Disable:
        return GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
    case Bias::PullUp:
        return GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
    case Bias::PullDown:
        return GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
    }
    return 0;
}

class LibgpiodInput final : public InputLine
{
public:
    LibgpiodInput(ChipHandle chip, gpiod_line *line, LineAddress address)
        : chip_(std::move(chip)), line_(line), address_(std::move(address))
    {}
    ~LibgpiodInput() override { gpiod_line_release(line_); }

    int fd() const override { return gpiod_line_event_get_fd(line_); }

    Result<unsigned> drainEvents() override
    {
        // Bounded: a line bouncing faster than we read still lets the loop go on (the debounce reads the level).
        unsigned drained = 0;
        const timespec now{0, 0};
        for (int round = 0; round < 16; ++round) {
            const int pending = gpiod_line_event_wait(line_, &now);
            if (pending < 0)
                return makeError(ErrorCode::DeviceLost, address_.describe() + ": " + errnoText());
            if (pending == 0)
                break;
            gpiod_line_event events[16];
            const int read = gpiod_line_event_read_multiple(line_, events, 16);
            if (read < 0)
                return makeError(ErrorCode::DeviceLost, address_.describe() + ": " + errnoText());
            drained += unsigned(read);
        }
        return drained;
    }

    Result<bool> active() override
    {
        const int value = gpiod_line_get_value(line_);
        if (value < 0)
            return makeError(ErrorCode::DeviceLost, address_.describe() + ": " + errnoText());
        return value == 1;
    }

private:
    ChipHandle chip_;
    gpiod_line *line_;
    LineAddress address_;
};

class LibgpiodOutput final : public OutputLine
{
public:
    LibgpiodOutput(ChipHandle chip, gpiod_line *line, LineAddress address)
        : chip_(std::move(chip)), line_(line), address_(std::move(address))
    {}
    ~LibgpiodOutput() override { gpiod_line_release(line_); }

    Status setActive(bool active) override
    {
        if (gpiod_line_set_value(line_, active ? 1 : 0) != 0)
            return makeError(ErrorCode::DeviceLost, address_.describe() + ": " + errnoText());
        return Ok{};
    }

private:
    ChipHandle chip_;
    gpiod_line *line_;
    LineAddress address_;
};

class LibgpiodProvider final : public LineProvider
{
public:
    Result<std::unique_ptr<InputLine>> requestInput(const InputRequest &input, const std::string &consumer) override
    {
        auto found = findLine(input.line);
        if (!found)
            return found.error();
        auto &[chip, line] = *found;
        gpiod_line_request_config config{};
        config.consumer = consumer.c_str();
        config.request_type = GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES;
        config.flags = (input.activeLow ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0) | biasFlags(input.bias);
        if (auto requested = request(line, input.line, config, 0); !requested)
            return requested.error();
        return std::unique_ptr<InputLine>(std::make_unique<LibgpiodInput>(std::move(chip), line, input.line));
    }

    Result<std::unique_ptr<OutputLine>> requestOutput(const OutputRequest &output, const std::string &consumer) override
    {
        auto found = findLine(output.line);
        if (!found)
            return found.error();
        auto &[chip, line] = *found;
        gpiod_line_request_config config{};
        config.consumer = consumer.c_str();
        config.request_type = GPIOD_LINE_REQUEST_DIRECTION_OUTPUT;
        config.flags = output.activeLow ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
        if (auto requested = request(line, output.line, config, output.active ? 1 : 0); !requested)
            return requested.error();
        return std::unique_ptr<OutputLine>(std::make_unique<LibgpiodOutput>(std::move(chip), line, output.line));
    }
};

} // namespace

std::unique_ptr<LineProvider> makeLineProvider()
{
    return std::make_unique<LibgpiodProvider>();
}

bool haveLibgpiod()
{
    return true;
}

Result<std::vector<ChipInfo>> listChips()
{
    std::vector<ChipInfo> chips;
    gpiod_chip_iter *iter = gpiod_chip_iter_new();
    if (!iter) {
        if (errno == ENOENT)
            return chips;
        return makeError(ErrorCode::Io, "listing GPIO chips: " + errnoText());
    }
    gpiod_chip *chip;
    gpiod_foreach_chip(iter, chip)
    {
        ChipInfo info{gpiod_chip_name(chip), gpiod_chip_label(chip), std::string("/dev/") + gpiod_chip_name(chip), {}};
        const unsigned count = gpiod_chip_num_lines(chip);
        for (unsigned offset = 0; offset < count; ++offset) {
            gpiod_line *line = gpiod_chip_get_line(chip, offset);
            if (!line)
                continue;
            const char *name = gpiod_line_name(line);
            const char *consumer = gpiod_line_consumer(line);
            info.lines.push_back({offset, name ? name : "", consumer ? consumer : "",
                                  gpiod_line_direction(line) == GPIOD_LINE_DIRECTION_OUTPUT,
                                  gpiod_line_active_state(line) == GPIOD_LINE_ACTIVE_STATE_LOW});
        }
        chips.push_back(std::move(info));
    }
    gpiod_chip_iter_free(iter);
    return chips;
}

} // namespace overlayd
