// SPDX-License-Identifier: Apache-2.0
// [daemon], [source] (with its synthetic, replay, v4l2 and libcamera sub-tables) and [[sink]].
#include "config/config_sections.h"

#include <cerrno>
#include <filesystem>
#include <map>

#include <sys/stat.h>

#include "base/regular_file.h"
#include "config/limits.h"
#include "drivers/files/path_pattern.h"
#include "drivers/source_kind_names.h"
#include "media/frame.h"
#include "media/pixel_format.h"

namespace overlayd {

namespace {

constexpr size_t kMaxLibcameraControls = 64; // libcamera itself defines fewer than 60

void readPixelFormat(TableReader &source, const PixelFormatInfo *&out)
{
    const auto name = source.string("format");
    if (!name)
        return;
    if (const PixelFormatInfo *format = pixelFormatFromName(*name)) {
        out = format;
        return;
    }
    std::vector<std::string> names;
    std::string list;
    for (const PixelFormatInfo &info : pixelFormats()) {
        names.emplace_back(info.name);
        list += (list.empty() ? "" : ", ") + std::string(info.name);
    }
    std::string message = "unknown pixel format '" + *name + "' (supported: " + list + ")";
    if (const std::string guess = closestMatch(*name, names); !guess.empty())
        message += "; did you mean '" + guess + "'?";
    source.problem("format", std::move(message));
}

void readSynthetic(TableReader &synthetic, SyntheticOptions &out)
{
    if (auto pattern = synthetic.choice<SyntheticPattern>(
            "pattern", {{"colour-bars", SyntheticPattern::ColourBars},
                        {"checkerboard", SyntheticPattern::Checkerboard},
                        {"moving-gradient", SyntheticPattern::MovingGradient},
                        {"noise", SyntheticPattern::Noise},
                        {"checkerboard-scene", SyntheticPattern::CheckerboardScene}}))
        out.pattern = *pattern;
    if (auto seed = synthetic.integer("seed", 0, INT64_MAX))
        out.seed = uint64_t(*seed);
    if (auto px = synthetic.integer("checker_px", 1, kMaxFrameDimension))
        out.checkerPx = unsigned(*px);
    if (auto metres = synthetic.positive("checker_metres", 1e6))
        out.checkerMetres = *metres;
    if (auto stall = synthetic.integer("stall_after_frames", 0, INT64_MAX))
        out.stallAfterFrames = uint64_t(*stall);
    synthetic.finish();
}

// Why a replay's recording cannot be read, or empty. A missing file is known without a device, so check-config
// refuses it as run would when it opens the source (a file the source cannot open for another reason, as a
// permission, is left to the source). An image sequence is checked by its first file. The words are the source's
// (base/regular_file.h), after the path as written and, when that differs, the file looked for.
std::string replayFileProblem(const std::string &written, const ReplayOptions &replay)
{
    std::string first = replay.path;
    if (replay.format == ReplayFormat::Images || (replay.format == ReplayFormat::Auto && hasIndexPattern(first))) {
        auto numbered = formatIndex(replay.path, replay.firstIndex);
        if (!numbered)
            return numbered.error().message;
        first = *numbered;
    }
    std::string why;
    struct stat info {};
    if (::stat(first.c_str(), &info) != 0) {
        if (errno != ENOENT && errno != ENOTDIR)
            return {};
        why = "does not exist";
    } else if (!S_ISREG(info.st_mode)) {
        why = std::string("is ") + fileKindName(unsigned(info.st_mode)) + ", not a regular file";
    } else {
        return {};
    }
    return written + ": " + why + (first != written ? " (" + first + ")" : "");
}

void readReplay(TableReader &replay, const std::string &baseDirectory, bool used, ReplayOptions &out)
{
    auto path = replay.string("path");
    if (path)
        out.path = resolvePath(baseDirectory, *path);
    else if (!replay.has("path"))
        replay.problem("path", "missing: a replay source needs the file to read");
    if (auto format = replay.choice<ReplayFormat>("format", {{"auto", ReplayFormat::Auto},
                                                             {"y4m", ReplayFormat::Y4m},
                                                             {"raw", ReplayFormat::Raw},
                                                             {"images", ReplayFormat::Images}}))
        out.format = *format;
    if (auto loop = replay.boolean("loop"))
        out.loop = *loop;
    if (auto first = replay.integer("first_index", 0, 1000000000))
        out.firstIndex = unsigned(*first);
    if (path && used)
        if (const std::string problem = replayFileProblem(*path, out); !problem.empty())
            replay.problem("path", problem);
    replay.finish();
}

void readV4l2(TableReader &v4l2, V4l2CaptureOptions &out)
{
    if (auto device = v4l2.string("device"))
        out.device = *device;
    if (auto buffers = v4l2.integer("buffers", 2, 32)) // streaming needs one queued while another is out
        out.bufferCount = unsigned(*buffers);
    if (auto timeout = v4l2.positive("no_signal_timeout", 3600.0))
        out.noSignalTimeoutSec = *timeout;
    v4l2.finish();
}

// Controls are checked by name and value here against libcamera's registry (check-config has no camera: the type's
// range, NaN, array controls); the camera's own ranges when it opens.
void readControls(TableReader &libcamera, std::vector<ControlSetting> &out)
{
    const toml::node *node = libcamera.node("controls");
    if (!node)
        return;
    const toml::table *controls = node->as_table();
    if (!controls) {
        libcamera.problemAt(*node, libcamera.keyPath("controls"),
                            std::string("expected a table such as { AeEnable = true }, got ") + typeName(*node));
        return;
    }
    if (controls->size() > kMaxLibcameraControls) {
        libcamera.problemAt(*node, libcamera.keyPath("controls"),
                            "at most " + std::to_string(kMaxLibcameraControls) + " controls");
        return;
    }
    if (!libcameraBuiltIn())
        return; // no registry to check names against: every control would be "unknown"; the kind says why
    for (const auto &[key, value] : *controls) {
        const std::string name(key.str()), path = libcamera.keyPath("controls") + "." + name;
        const auto kind = libcameraControlKind(name);
        if (!kind) {
            const std::string guess = closestMatch(name, libcameraControlNames());
            libcamera.problemAt(
                value, path, "unknown libcamera control" + (guess.empty() ? "" : " (did you mean '" + guess + "'?)"));
            continue;
        }
        ControlSetting setting{name, false, ""};
        if (*kind == ControlValueKind::Bool && value.is_boolean())
            setting.value = value.as_boolean()->get();
        else if (*kind == ControlValueKind::Integer && value.is_integer())
            setting.value = value.as_integer()->get();
        else if (*kind == ControlValueKind::Float && (value.is_number()))
            setting.value = value.is_integer() ? double(value.as_integer()->get()) : value.as_floating_point()->get();
        else {
            const char *wanted = *kind == ControlValueKind::Bool      ? "true or false"
                                 : *kind == ControlValueKind::Integer ? "an integer"
                                 : *kind == ControlValueKind::Float   ? "a number"
                                                                      : "nothing a config can give";
            libcamera.problemAt(value, path, std::string("expected ") + wanted + ", got " + typeName(value));
            continue;
        }
        if (const std::string problem = libcameraControlProblem(setting); !problem.empty()) {
            libcamera.problemAt(value, path, problem); // what building the camera's controls would refuse
            continue;
        }
        const auto &begin = value.source().begin;
        setting.where = libcamera.problems().file() + ":" + std::to_string(begin.line) + ":" +
                        std::to_string(begin.column) + ": " + path;
        out.push_back(std::move(setting));
    }
}

void readLibcamera(TableReader &libcamera, LibcameraOptions &out)
{
    if (auto camera = libcamera.string("camera")) {
        if (camera->empty() || camera->size() > 256)
            libcamera.problem("camera", "expected an index, a camera id or part of a model name (1..256 characters)");
        else
            out.camera = *camera;
    }
    if (auto role = libcamera.choice<StreamRole>("role", {{"viewfinder", StreamRole::Viewfinder},
                                                          {"video", StreamRole::VideoRecording},
                                                          {"still-capture", StreamRole::StillCapture}}))
        out.role = *role;
    if (auto buffers = libcamera.integer("buffers", 2, 32))
        out.bufferCount = unsigned(*buffers);
    if (auto timeout = libcamera.positive("no_signal_timeout", 3600.0))
        out.noSignalTimeoutSec = *timeout;
    if (auto transform = libcamera.choice<ImageTransform>("transform", {{"identity", ImageTransform::Identity},
                                                                        {"hflip", ImageTransform::HFlip},
                                                                        {"vflip", ImageTransform::VFlip},
                                                                        {"rot180", ImageTransform::Rot180}}))
        out.transform = *transform;
    readControls(libcamera, out.controls);
    libcamera.finish();
}

void readStream(TableReader &source, SourceOptions &out)
{
    readPixelFormat(source, out.pixelFormat);
    if (auto width = source.integer("width", 1, kMaxFrameDimension))
        out.width = unsigned(*width);
    if (auto height = source.integer("height", 1, kMaxFrameDimension))
        out.height = unsigned(*height);
    if (auto fps = source.positive("fps", 1000.0))
        out.fps = *fps;
    if (auto colorimetry =
            source.choice<Colorimetry>("colorimetry", {{"bt601-limited", {YcbcrMatrix::Bt601, ColourRange::Limited}},
                                                       {"bt601-full", {YcbcrMatrix::Bt601, ColourRange::Full}},
                                                       {"bt709-limited", {YcbcrMatrix::Bt709, ColourRange::Limited}},
                                                       {"bt709-full", {YcbcrMatrix::Bt709, ColourRange::Full}}}))
        out.colorimetry = *colorimetry;
}

} // namespace

std::string resolvePath(const std::string &baseDirectory, const std::string &path)
{
    if (path.empty() || path == "-" || baseDirectory.empty() || std::filesystem::path(path).is_absolute())
        return path;
    return (std::filesystem::path(baseDirectory) / path).lexically_normal().string();
}

void readDaemon(TableReader &root, DaemonSettings &out)
{
    auto daemon = root.table("daemon");
    if (!daemon)
        return;
    if (auto level = daemon->choice<LogLevel>("log_level", {{"debug", LogLevel::Debug},
                                                            {"info", LogLevel::Info},
                                                            {"notice", LogLevel::Notice},
                                                            {"warning", LogLevel::Warning},
                                                            {"error", LogLevel::Error}}))
        out.logLevel = *level;
    if (auto interval = daemon->number("stats_interval", 0.0, 86400.0)) {
        if (*interval != 0.0 && *interval < kMinStatsIntervalSec)
            daemon->problem("stats_interval", "out of range: must be 0 (off) or in [0.1, 86400] s");
        else
            out.statsIntervalSec = *interval;
    }
    daemon->finish();
}

void readSource(TableReader &root, const std::string &baseDirectory, SourceOptions &out)
{
    auto source = root.table("source");
    if (!source)
        return;
    if (auto kind = source->choice<SourceKind>("kind", kSourceKindNames)) {
        out.kind = *kind;
        if (out.kind == SourceKind::Libcamera && !libcameraBuiltIn())
            source->problem("kind", "this overlayd was built without libcamera (CMake option OVERLAYD_LIBCAMERA)");
    }
    readStream(*source, out);
    if (auto synthetic = source->table("synthetic"))
        readSynthetic(*synthetic, out.synthetic);
    if (auto replay = source->table("replay"))
        readReplay(*replay, baseDirectory, out.kind == SourceKind::Replay, out.replay);
    else if (out.kind == SourceKind::Replay)
        source->problem("replay", "missing: kind = \"replay\" needs a [source.replay] table with its path");
    if (auto v4l2 = source->table("v4l2"))
        readV4l2(*v4l2, out.v4l2);
    if (auto libcamera = source->table("libcamera"))
        readLibcamera(*libcamera, out.libcamera);
    source->finish();
}

namespace {

// What two sinks must not share: "-" (stdout), or the file a path names, however it is spelled ("out/../a.y4m",
// "./a.y4m", a symlinked folder). Relative paths count from the working directory, as the sinks open them.
std::string outputIdentity(const std::string &path)
{
    if (path == "-")
        return path;
    std::error_code error;
    const std::filesystem::path absolute = std::filesystem::absolute(path, error);
    const std::filesystem::path resolved = error ? absolute : std::filesystem::weakly_canonical(absolute, error);
    return error ? std::filesystem::path(path).lexically_normal().string() : resolved.string();
}

} // namespace

// Output paths stay as written (relative to the daemon's working directory, where a user looks for them); only
// inputs (replay files, calibrations) resolve against the config file's folder. Two sinks on one file (or both on
// stdout) would interleave their frames into a file nothing reads: the second is refused at its path.
void readSinks(TableReader &root, std::vector<SinkOptions> &out, StreamOptions &encoded)
{
    std::map<std::string, std::string> writers; // output identity -> the first sink's key, "sink[0].path"
    std::string holder;                         // the sink with zero_copy = "on", "sink[0].zero_copy"
    std::map<std::string, std::string> names;   // sink name -> the key that gave it, "sink[0].name"
    for (TableReader &sink : root.tables("sink", kMaxSinks)) {
        if (isEncodedSink(sink)) {
            readEncodedSink(sink, encoded);
            continue;
        }
        const size_t before = sink.problems().size();
        SinkOptions options;
        options.name = sink.string("name", kMaxNameBytes).value_or("sink[" + std::to_string(out.size()) + "]");
        if (const auto [first, added] = names.emplace(options.name, sink.keyPath("name")); !added)
            sink.problem("name", "'" + options.name + "' is the name of " + first->second +
                                     " already: /state and /metrics tell sinks apart by name");
        if (auto kind = sink.choice<SinkKind>("kind", {{"y4m", SinkKind::Y4m},
                                                       {"raw", SinkKind::Raw},
                                                       {"snapshot", SinkKind::Snapshot},
                                                       {"null", SinkKind::Null},
                                                       {"v4l2", SinkKind::V4l2Output},
                                                       // Never chosen here (readEncodedSink reads it): listed so
                                                       // that an unknown kind's message names it.
                                                       {"rtsp", SinkKind::Null},
                                                       {"record", SinkKind::Null},
                                                       {"push", SinkKind::Null},
                                                       {"file", SinkKind::Null}}))
            options.kind = *kind;
        else if (!sink.has("kind"))
            sink.problem("kind", "missing: y4m | raw | snapshot | null | v4l2 | rtsp | record | push | file");
        if (auto path = sink.string("path")) {
            options.path = *path;
            const bool writes = options.kind != SinkKind::Null && !path->empty();
            const auto [first, added] =
                writes ? writers.emplace(outputIdentity(*path), sink.keyPath("path")) : std::pair(writers.end(), true);
            if (!added)
                sink.problem("path", (*path == "-" ? "stdout" : "'" + *path + "'") + " is written by " + first->second +
                                         " already: two sinks cannot share an output");
        } else if (!sink.has("path") && options.kind != SinkKind::Null && sink.has("kind"))
            sink.problem("path", "missing: this sink writes to a path");
        if (auto every = sink.integer("every", 1, 1000000))
            options.every = unsigned(*every);
        if (auto quality = sink.integer("jpeg_quality", 1, 100))
            options.jpegQuality = unsigned(*quality);
        if (auto depth = sink.integer("queue_depth", 1, 64))
            options.queueDepth = unsigned(*depth);
        if (auto drop = sink.choice<DropPolicy>(
                "drop", {{"oldest", DropPolicy::DropOldest}, {"newest", DropPolicy::DropNewest}}))
            options.dropPolicy = *drop;
        if (auto buffers = sink.integer("buffers", 2, 32))
            options.bufferCount = unsigned(*buffers);
        if (auto zeroCopy = sink.choice<ZeroCopy>(
                "zero_copy", {{"auto", ZeroCopy::Auto}, {"on", ZeroCopy::On}, {"off", ZeroCopy::Off}})) {
            options.zeroCopy = *zeroCopy;
            if (options.kind != SinkKind::V4l2Output)
                sink.problem("zero_copy", "only a kind = \"v4l2\" sink can take the capture buffers themselves");
            else if (options.zeroCopy == ZeroCopy::On && !holder.empty())
                sink.problem("zero_copy",
                             "only one sink can hold the camera's buffers, and " + holder + " = \"on\" already does");
            else if (options.zeroCopy == ZeroCopy::On)
                holder = sink.keyPath("zero_copy");
        }
        sink.finish();
        // What building the sink would refuse (run does it before the first frame), at the key.
        if (sink.problems().size() == before)
            if (const auto problem = checkSinkOptions(options))
                sink.problem(problem->key, problem->message);
        out.push_back(std::move(options));
    }
}

} // namespace overlayd
