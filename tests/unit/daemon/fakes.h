// SPDX-License-Identifier: Apache-2.0
// Fakes of the pipeline's stages for the daemon's unit tests: a scripted source, a recording (optionally slow)
// sink, a renderer that marks frames, and a notifier that records what systemd would have been told.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "control/scene_control.h"
#include "daemon/stages.h"
#include "daemon/systemd_notify.h"
#include "media/frame_buffer.h"
#include "overlay/overlay_renderer.h"

namespace overlayd::test {

StreamFormat greyFormat(unsigned width = 64, unsigned height = 48, double fps = 30.0);

// Delivers frames whose first byte is the frame's sequence number (mod 256), unless the script says otherwise.
class FakeSource : public FrameSource
{
public:
    struct Shared {
        std::deque<Error> script; // consumed one per nextFrame(); empty: a frame
        int starts = 0, stops = 0;
        std::deque<Error> startErrors;    // consumed one per start()
        int running = 0, mostRunning = 0; // sources started and not yet stopped: now, and at most at once
    };
    FakeSource(std::shared_ptr<Shared> shared, StreamFormat format);
    Result<StreamFormat> start() override;
    void stop() override;
    int eventFd() const override { return -1; }
    Result<FrameLease> nextFrame() override;
    std::string describe() const override { return "fake source"; }

private:
    std::shared_ptr<Shared> shared_;
    StreamFormat format_;
    std::optional<FrameBuffer> buffer_;
    uint64_t sequence_ = 0;
    bool started_ = false;
};

// Records the first byte and sequence of each written frame; while `gate` is closed, write() blocks (a slow sink).
class RecordingSink : public FrameSink
{
public:
    struct Shared {
        std::mutex mutex;
        std::condition_variable changed;
        bool gateOpen = true;
        std::vector<uint8_t> firstBytes;
        std::vector<uint8_t> lastBytes; // where MarkingRenderer writes
        std::vector<uint8_t> maxima;    // the brightest byte of plane 0
        std::vector<uint64_t> sequences;
        int opens = 0, closes = 0;
        int failOpens = 0; // this many open() calls fail, from the next one on
        int entered = 0;   // write() calls begun (a blocked one included)
        void waitEntered(int count);
        void setGate(bool open);
        size_t written();
    };
    RecordingSink(std::shared_ptr<Shared> shared, std::string name) : shared_(std::move(shared)), name_(name) {}
    Status open(const StreamFormat &) override;
    Status write(const FrameView &frame, const FrameMetadata &metadata) override;
    Status close() override;
    std::string describe() const override { return name_; }

private:
    std::shared_ptr<Shared> shared_;
    std::string name_;
};

// Sets the frame's last byte to `mark`, so tests can tell which renderer blended a frame.
class MarkingRenderer : public OverlayRenderer
{
public:
    explicit MarkingRenderer(uint8_t mark) : mark_(mark) {}
    Status setCamera(const Camera &) override { return Ok{}; }
    Status setLayerEnabled(std::string_view, bool) override { return Ok{}; }
    Status setSlotText(std::string_view, std::string_view) override { return Ok{}; }
    Status setGuideSteering(std::string_view, std::optional<double>) override { return Ok{}; }
    Status setWorldPoints(std::string_view, std::span<const glm::dvec3>) override { return Ok{}; }
    std::vector<std::string> layerNames() const override { return {}; }
    Status blend(const FrameView &frame, const FrameMetadata &, double) override;

private:
    uint8_t mark_;
};

// Records what SceneControl asked of it (its layer names are the ones scene_control_test's scene uses).
class RecordingRenderer : public OverlayRenderer
{
public:
    Status setCamera(const Camera &camera) override
    {
        cameras.push_back(camera.projection().matrix());
        return Ok{};
    }
    Status setLayerEnabled(std::string_view layer, bool enabled) override
    {
        layers.emplace_back(std::string(layer), enabled);
        return Ok{};
    }
    std::vector<std::string> layerNames() const override { return {"grid", "labels"}; }
    Status setSlotText(std::string_view slot, std::string_view text) override
    {
        slots.emplace_back(std::string(slot), std::string(text));
        return Ok{};
    }
    Status setGuideSteering(std::string_view annotation, std::optional<double> steeringDeg) override
    {
        steerings.emplace_back(std::string(annotation), steeringDeg);
        return Ok{};
    }
    Status setWorldPoints(std::string_view annotation, std::span<const glm::dvec3> points) override
    {
        worldPoints.emplace_back(std::string(annotation), std::vector<glm::dvec3>(points.begin(), points.end()));
        return Ok{};
    }
    Status blend(const FrameView &, const FrameMetadata &, double) override { return Ok{}; }

    std::vector<std::pair<std::string, std::vector<glm::dvec3>>> worldPoints;
    std::vector<std::pair<std::string, std::optional<double>>> steerings;
    std::vector<glm::dmat4> cameras;
    std::vector<std::pair<std::string, bool>> layers;
    std::vector<std::pair<std::string, std::string>> slots;
};

// A test with a SceneControl whose renderers record what they are asked (`renderer`: the one built last) and one
// stream attached (attachStream: build, hand to the "pipeline" `live`, attach), as the daemon does it.
struct RecordingSceneTest : ::testing::Test {
    RecordingRenderer *renderer = nullptr;
    SceneControl control{
        [this](const OverlayScene &, const Camera &, const StreamFormat &) -> Result<std::unique_ptr<OverlayRenderer>> {
            auto made = std::make_unique<RecordingRenderer>();
            renderer = made.get();
            return std::unique_ptr<OverlayRenderer>(std::move(made));
        }};
    std::unique_ptr<OverlayRenderer> live;

    void attachStream()
    {
        auto built = control.build(greyFormat());
        ASSERT_TRUE(built.ok());
        live = std::move(*built);
        control.attach(live.get(), greyFormat());
    }
};

class RecordingNotifier : public SystemdNotifier
{
public:
    void ready() override { events.push_back("READY"); }
    void reloading() override { events.push_back("RELOADING"); }
    void stopping() override { events.push_back("STOPPING"); }
    void status(std::string_view line) override { events.push_back("STATUS=" + std::string(line)); }
    void watchdog() override { events.push_back("WATCHDOG"); }
    int count(const std::string &event) const;
    std::string lastStatus() const;
    std::vector<std::string> events;
};

} // namespace overlayd::test
