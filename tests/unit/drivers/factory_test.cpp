// SPDX-License-Identifier: Apache-2.0
// The factories refuse bad options before opening or allocating anything, with a message naming the value.
#include <gtest/gtest.h>

#include "drivers/sink_options.h"
#include "drivers/source_options.h"

namespace overlayd {
namespace {

std::string sourceError(void (*change)(SourceOptions &))
{
    SourceOptions o;
    o.synthetic.pattern = SyntheticPattern::ColourBars;
    change(o);
    auto source = makeSource(o);
    return source ? std::string() : source.error().message;
}

TEST(Factories, SourceOptionsAreValidated)
{
    EXPECT_EQ(sourceError([](SourceOptions &) {}), "");
    // A format name is resolved (and an unknown one refused, naming it) by the config loader: see
    // config_tests' Schema.UnknownPixelFormatNamesTheLineAndKey; options made in code can only fail to name one.
    EXPECT_NE(sourceError([](SourceOptions &o) { o.pixelFormat = nullptr; }).find("pixel format"), std::string::npos);
    EXPECT_NE(sourceError([](SourceOptions &o) { o.fps = 0; }).find("fps"), std::string::npos);
    EXPECT_NE(sourceError([](SourceOptions &o) { o.width = 0; }).find("0x720"), std::string::npos);
    EXPECT_NE(sourceError([](SourceOptions &o) { o.width = 100000, o.height = 100000; }).find("limit"),
              std::string::npos);
    EXPECT_NE(
        sourceError([](SourceOptions &o) { o.synthetic.pattern = SyntheticPattern::CheckerboardScene; }).find("camera"),
        std::string::npos);
    EXPECT_NE(sourceError([](SourceOptions &o) { o.kind = SourceKind::Replay; }).find("path"), std::string::npos);
    EXPECT_NE(sourceError([](SourceOptions &o) {
                  o.kind = SourceKind::Replay, o.replay.path = "x.raw", o.fps = -1;
              }).find("fps"),
              std::string::npos);
    EXPECT_NE(
        sourceError([](SourceOptions &o) { o.kind = SourceKind::Replay, o.replay.path = "frames/%s.png"; }).find("%d"),
        std::string::npos);
}

std::string sinkError(void (*change)(SinkOptions &))
{
    SinkOptions o;
    change(o);
    auto sink = makeSink(o);
    return sink ? std::string() : sink.error().message;
}

TEST(Factories, SinkOptionsAreValidated)
{
    EXPECT_EQ(sinkError([](SinkOptions &) {}), ""); // null
    EXPECT_NE(sinkError([](SinkOptions &o) { o.kind = SinkKind::Y4m; }).find("path"), std::string::npos);
    EXPECT_NE(sinkError([](SinkOptions &o) { o.kind = SinkKind::Raw; }).find("path"), std::string::npos);
    EXPECT_NE(sinkError([](SinkOptions &o) { o.kind = SinkKind::Snapshot, o.path = "a.bmp"; }).find(".png"),
              std::string::npos);
    EXPECT_NE(
        sinkError([](SinkOptions &o) { o.kind = SinkKind::Snapshot, o.path = "a.png", o.every = 0; }).find("every"),
        std::string::npos);
    EXPECT_NE(sinkError([](SinkOptions &o) {
                  o.kind = SinkKind::Snapshot, o.path = "a.jpg", o.jpegQuality = 101;
              }).find("101"),
              std::string::npos);
    EXPECT_NE(sinkError([](SinkOptions &o) { o.kind = SinkKind::Snapshot, o.path = "a%d%d.png"; }).find("%d"),
              std::string::npos);
}

} // namespace
} // namespace overlayd
