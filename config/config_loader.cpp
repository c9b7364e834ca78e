// SPDX-License-Identifier: Apache-2.0
// loadConfigFile / loadConfigText: parse with toml++, read every section, then check what spans sections (frame
// names, the camera composed through projection/), collecting every problem in one pass.
#include "config/daemon_config.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "base/regular_file.h"
#include "config/config_sections.h"
#include "config/limits.h"
#include "config/live_drop_in.h"
#include "config/nesting_depth.h"

namespace overlayd {

namespace {

std::vector<std::string> frameNames(const std::vector<FrameSpec> &frames)
{
    std::vector<std::string> names{SceneGraph::kWorld};
    for (const FrameSpec &frame : frames)
        names.push_back(frame.name);
    return names;
}

void checkFrameName(TableReader &table, std::string_view key, const std::string &name,
                    const std::vector<std::string> &names)
{
    if (std::find(names.begin(), names.end(), name) != names.end())
        return;
    std::string message = "unknown frame '" + name + "' (define it in a [[frame]] table)";
    if (const std::string guess = closestMatch(name, names); !guess.empty())
        message += "; did you mean '" + guess + "'?";
    table.problem(key, std::move(message));
}

// Each frame's scale and translation are in range, but a chain of them multiplies: 20 frames scaled by 1000 reach
// 1e60, and a few more inf. The composed transform of each frame must stay within kMaxComposedMagnitude.
void checkComposed(std::vector<TableReader> &tables, const std::vector<FrameSpec> &frames, const SceneGraph &graph)
{
    for (size_t i = 0; i < tables.size() && i < frames.size(); ++i) {
        const auto world = graph.worldMatrix(frames[i].name);
        if (!world)
            continue;
        double largest = 0.0;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                largest = std::isfinite((*world)[c][r]) ? std::max(largest, std::abs((*world)[c][r])) : INFINITY;
        if (largest > kMaxComposedMagnitude) {
            std::ostringstream got;
            got << largest << "; at most " << kMaxComposedMagnitude << " is allowed";
            tables[i].problemAtTable("its transform from the world (the product of its parents' scales and "
                                     "translations and its own) reaches " +
                                     got.str());
            return; // its children would only repeat it
        }
    }
}

// Parents and annotation frames must name frames; the scene graph itself catches duplicates and cycles.
std::optional<SceneGraph> checkFrames(TableReader &root, DaemonConfig &config)
{
    const std::vector<std::string> names = frameNames(config.scene.frames);
    std::vector<TableReader> frames = root.tables("frame", kMaxFrames, false); // readFrames reported the count
    for (size_t i = 0; i < frames.size() && i < config.scene.frames.size(); ++i)
        if (frames[i].has("parent"))
            checkFrameName(frames[i], "parent", config.scene.frames[i].parent, names);
    std::vector<TableReader> annotations = root.tables("annotation", kMaxAnnotations, false);
    for (size_t i = 0; i < annotations.size() && i < config.scene.annotations.size(); ++i)
        if (annotations[i].has("frame"))
            checkFrameName(annotations[i], "frame", config.scene.annotations[i].frame, names);
    auto graph = SceneGraph::create(config.scene.frames);
    if (!graph) {
        root.problem("frame", graph.error().message);
        return std::nullopt;
    }
    config.scene.graph = *graph;
    checkComposed(frames, config.scene.frames, *graph);
    return graph.value();
}

// False when the camera or viewport had problems of their own: composing the Camera would only repeat them.
bool readCamera(TableReader &root, const std::string &baseDirectory, DaemonConfig &config, CameraKeys &keys)
{
    const size_t before = root.problems().size();
    if (auto viewport = root.table("viewport"))
        readViewport(*viewport, config.camera.viewport);
    auto camera = root.table("camera");
    if (camera) {
        config.camera.mountFrame = camera->string("frame").value_or(SceneGraph::kWorld);
        readPose(*camera, config.camera.pose, &config.camera.poseKeys);
        readIntrinsics(*camera, baseDirectory, config.camera, keys);
        camera->finish();
    }
    return root.problems().size() == before;
}

// Composes the Camera for the configured stream size the way the daemon will, so that projection/'s refusals
// land on the keys behind them.
void checkCamera(TableReader &root, DaemonConfig &config, const SceneGraph &graph, const CameraKeys &keys)
{
    CameraSpec &spec = config.camera;
    auto camera = root.table("camera");
    if (auto mount = graph.worldMatrix(spec.mountFrame))
        spec.worldFromMount = *mount;
    else if (camera)
        checkFrameName(*camera, "frame", spec.mountFrame, frameNames(config.scene.frames));
    auto viewport = spec.buildViewport(config.source.width, config.source.height);
    if (!viewport) {
        root.problem("viewport", viewport.error().message);
        return;
    }
    if (auto region = spec.checkCalibrationRegion(*viewport); !region) {
        if (camera)
            camera->problem("calibration_crop", region.error().message);
        return;
    }
    auto projection = spec.buildProjection(*viewport);
    if (!projection) {
        if (camera)
            camera->problem(keys.intrinsics, projection.error().message);
        return;
    }
    if (auto built = Camera::create(spec.view(), *projection, spec.distortion, *viewport); !built && camera)
        camera->problem(keys.hasDistortion ? "distortion" : keys.intrinsics, built.error().message);
}

Error summarize(const Problems &found, std::vector<ConfigProblem> &problems)
{
    problems = found.sorted();
    std::string message = std::to_string(problems.size()) + " problem(s) in " + found.file() + ":";
    for (const ConfigProblem &problem : problems)
        message += "\n" + problem.format();
    return makeError(ErrorCode::ConfigError, message);
}

// Every section of a parsed file (with its drop-in merged), then what spans sections.
Result<DaemonConfig> readRoot(const toml::table &root, const std::string &name, const std::string &baseDirectory,
                              Problems &found, std::vector<ConfigProblem> &problems)
{
    DaemonConfig result;
    result.path = name;
    TableReader reader(root, "", found);
    CameraKeys keys;
    readDaemon(reader, result.daemon);
    readSource(reader, baseDirectory, result.source);
    readSinks(reader, result.sinks, result.stream);
    readEncoder(reader, result.stream);
    readFrames(reader, result.scene.frames);
    readAnnotations(reader, baseDirectory, result.scene.annotations);
    readGpio(reader, result.scene.annotations, result.gpio);
    readHttp(reader, baseDirectory, result.http);
    resolveRtspAccess(reader, result.http, result.stream);
    readWebrtc(reader, result.http.enabled, result.stream.webrtc);
    readInputs(reader, baseDirectory, result.scene, result.inputs);
    const bool cameraRead = readCamera(reader, baseDirectory, result, keys);
    reader.finish();
    auto graph = checkFrames(reader, result);
    if (graph && cameraRead)
        checkCamera(reader, result, *graph, keys);
    if (!found.empty())
        return summarize(found, problems);
    return result;
}

// The drop-in's [camera] over the main file's: its pose replaces every pose key, its intrinsics form (if any)
// every intrinsics form key (and a calibration file, unless the form is pinhole, whose keys are read over the
// calibration's); anything else in it is read as given (and judged by the same readers).
void mergeDropIn(toml::table &root, toml::table &dropIn)
{
    toml::table *from = dropIn["camera"].as_table();
    if (!from) {
        root.insert_or_assign("camera.live", std::move(dropIn)); // reported as an unknown key, at the drop-in
        return;
    }
    toml::table *into = root["camera"].as_table();
    if (!into) {
        root.insert_or_assign("camera", std::move(*from));
        return;
    }
    auto replaces = [&](const auto &keys) {
        for (std::string_view key : keys)
            if (from->contains(key)) {
                for (std::string_view old : keys)
                    into->erase(old);
                return;
            }
    };
    replaces(kPoseKeys);
    replaces(kIntrinsicsFormKeys);
    for (std::string_view key : kIntrinsicsFormKeys)
        if (key != "pinhole" && key != "fov_axis" && from->contains(key))
            into->erase("calibration");
    for (auto &&[key, value] : *from)
        into->insert_or_assign(key, std::move(value));
}

// One TOML text into `into`; false, with the problem recorded against `file`, when it nests too deep (toml++ limits
// nested values but recurses once per dotted key part, and overflows the stack on tens of thousands) or does not
// parse. toml++ stops at the first syntax error: nothing after it can be read reliably.
bool parseToml(std::string_view text, const std::string &file, toml::table &into, Problems &found)
{
    if (auto deep = findTooDeep(text, TextSyntax::Toml)) {
        found.add(deep->line, deep->column, "",
                  "nested deeper than " + std::to_string(kMaxNestingDepth) +
                      " levels (arrays, inline tables and the parts of dotted keys and table names)",
                  file);
        return false;
    }
    try {
        into = toml::parse(text, file);
    } catch (const toml::parse_error &e) {
        found.add(e.source().begin.line, e.source().begin.column, "", "syntax error: " + std::string(e.description()),
                  file);
        return false;
    }
    return true;
}

// The file's text, or the problem that it cannot be one (missing, not a regular file, too large, unreadable).
std::optional<std::string> readConfigText(const std::string &path, Problems &found)
{
    auto text = readRegularFile(path, kMaxConfigFileBytes);
    if (!text) {
        found.add(0, 0, "", "the config file " + text.error().message, path);
        return std::nullopt;
    }
    return std::move(*text);
}

} // namespace

Result<DaemonConfig> loadConfigText(std::string_view text, const std::string &name, const std::string &baseDirectory,
                                    std::vector<ConfigProblem> &problems)
{
    problems.clear();
    Problems found(name);
    toml::table root;
    if (!parseToml(text, name, root, found))
        return summarize(found, problems);
    return readRoot(root, name, baseDirectory, found, problems);
}

Result<DaemonConfig> loadConfigFile(const std::string &path, std::vector<ConfigProblem> &problems)
{
    problems.clear();
    Problems found(path);
    const auto text = readConfigText(path, found);
    if (!text)
        return summarize(found, problems);
    std::string base = std::filesystem::path(path).parent_path().string();
    base = base.empty() ? "." : base;
    const std::string dropInPath = liveDropInPath(path);
    std::error_code absent;
    if (!std::filesystem::exists(dropInPath, absent))
        return loadConfigText(*text, path, base, problems);
    toml::table root, dropIn;
    const auto dropInText = readConfigText(dropInPath, found);
    if (!dropInText || !parseToml(*text, path, root, found) || !parseToml(*dropInText, dropInPath, dropIn, found))
        return summarize(found, problems);
    mergeDropIn(root, dropIn);
    return readRoot(root, path, base, found, problems);
}

} // namespace overlayd
