// SPDX-License-Identifier: Apache-2.0
// The command line, declared once with CLI11; its exceptions stay inside this file.
#include "tools/cli.h"

#include <CLI/CLI.hpp>

#include "base/logger.h"
#include "base/version.h"

namespace overlayd {

namespace {

// `overlayd --config F` and `overlayd F`-less invocations mean `run`: insert it unless a subcommand or a
// help/version flag is already there.
std::vector<std::string> withDefaultSubcommand(int argc, const char *const *argv)
{
    std::vector<std::string> args(argv + 1, argv + argc);
    for (const std::string &arg : args) {
        if (arg == "run" || arg == "check-config" || arg == "project" || arg == "render" || arg == "list-cameras" ||
            arg == "list-gpio" || arg == "unproject" || arg == "solve-pose" || arg == "--help" || arg == "-h" ||
            arg == "--version")
            return args;
    }
    args.insert(args.begin(), "run");
    return args;
}

} // namespace

CommandLine parseCommandLine(int argc, const char *const *argv)
{
    CommandLine line;
    std::string logLevel;
    CLI::App app{"overlayd: projects 3D annotations onto camera frames and writes the overlaid stream", "overlayd"};
    app.set_version_flag("--version", std::string("overlayd ") + overlaydVersion());
    app.require_subcommand(1);
    app.fallthrough(); // before add_subcommand: subcommands copy it, so --log-level works after them too
    app.add_option("--log-level", logLevel, "debug | info | notice | warning | error (overrides daemon.log_level)")
        ->check(CLI::IsMember({"debug", "info", "notice", "warning", "error"}))
        ->group("Logging (before or after the command)");
    app.footer("Examples:\n"
               "  overlayd run --config /etc/overlayd/overlayd.toml   the daemon (what overlayd.service runs)\n"
               "  overlayd check-config /etc/overlayd/overlayd.toml   validate before systemctl reload overlayd\n"
               "  overlayd COMMAND --help                             one command's options\n\n"
               "See overlayd(1) and overlayd.toml(5).");

    CLI::App *run = app.add_subcommand("run", "run the pipeline until SIGTERM/SIGINT; SIGHUP reloads (default)");
    run->add_option("--config,-c", line.configPath, "the TOML config file")->required()->check(CLI::ExistingFile);
    run->add_option("--frames", line.frames, "stop cleanly after N source frames (default: never)");
    run->footer("Example:\n  overlayd run --config /etc/overlayd/overlayd.toml\n"
                "Signals: SIGTERM and SIGINT stop it cleanly, SIGHUP reloads the config (kept if it is refused).");

    CLI::App *check = app.add_subcommand("check-config", "validate a config file and print every problem");
    check->add_option("file", line.configPath, "the TOML config file")->required();
    check->footer("Example:\n  overlayd check-config /etc/overlayd/overlayd.toml\n"
                  "Exit status: 0 valid, 2 refused (every problem printed as file:line:column: key: reason).");

    CLI::App *project = app.add_subcommand("project", "print where world points land in the configured camera");
    project->add_option("--config,-c", line.configPath, "the TOML config file")->required()->check(CLI::ExistingFile);
    project->add_flag("--json", line.json, "one JSON array, one object per point");
    project->add_option("--size", line.size,
                        "WxH: project for this stream size (intrinsics scale as for a camera "
                        "that negotiates it)");
    project->add_option("--points", line.pointsPath,
                        "a file of X Y Z lines in metres (spaces and/or commas, # comments; - reads stdin), as "
                        "[[input.path]] reads them; instead of the coordinates");
    project->add_option("coordinates", line.coordinates, "X Y Z [X Y Z ...] in metres (use -- before negatives)");
    project->footer("Example:\n  overlayd project --config demo.toml -- 1 0 0  2 -1 0");

    CLI::App *unproject = app.add_subcommand("unproject", "print each pixel's world ray and where it meets a plane");
    unproject->add_option("--config,-c", line.configPath, "the TOML config file")->required()->check(CLI::ExistingFile);
    unproject->add_flag("--json", line.json, "one JSON array, one object per pixel");
    unproject->add_option("--plane", line.plane, "nx ny nz d: the plane n.x + d = 0 (default 0 0 1 0, the ground)")
        ->expected(4)
        ->delimiter(' ');
    unproject->add_option("coordinates", line.coordinates, "U V [U V ...] pixels in the viewport's origin")->required();
    unproject->footer("Example:\n  overlayd unproject --config demo.toml --json 640 360");

    CLI::App *solve = app.add_subcommand("solve-pose", "the camera pose from world points and the pixels they are at");
    solve->add_option("--config,-c", line.configPath, "the TOML config file (intrinsics, lens, viewport, mount)")
        ->required()
        ->check(CLI::ExistingFile);
    solve->add_option("--points", line.pointsPath, "lines of x y z u v (world metres, pixel)")
        ->required()
        ->check(CLI::ExistingFile);
    solve
        ->add_option("--solver", line.solver,
                     "sqpnp (default: any 4+ points) | iterative (6+, or 4+ coplanar) | "
                     "ippe (4+ coplanar: a marked floor); each refined by Levenberg-Marquardt")
        ->check(CLI::IsMember({"sqpnp", "iterative", "ippe"}));
    solve->add_flag(
        "--write", line.write,
        "also write the pose, with the camera's intrinsics and lens, to NAME.live.toml beside the config (the "
        "drop-in the loader reads after it, which the browser page's Save writes too, merged with what it "
        "holds; the config itself is never rewritten)");
    solve->footer("Example:\n  overlayd solve-pose --config camera.toml --points marks.txt --write");

    CLI::App *render = app.add_subcommand("render", "run N frames unpaced into a file (.y4m, .yuv/.raw, %04d.png)");
    render->add_option("--config,-c", line.configPath, "the TOML config file")->required()->check(CLI::ExistingFile);
    render->add_option("--frames", line.frames, "how many frames")->required()->check(CLI::PositiveNumber);
    render->add_option("--output,-o", line.output, "output path; the extension picks the format")->required();
    render->footer("Example:\n  overlayd render --config demo.toml --frames 60 --output out/demo.y4m");

    CLI::App *list = app.add_subcommand("list-cameras", "every V4L2 and libcamera camera with what it offers");
    list->add_flag("--json", line.json, "one JSON array, one object per camera");
    list->footer("Example:\n  overlayd list-cameras --json");
    CLI::App *listGpio = app.add_subcommand("list-gpio", "every GPIO chip and its lines (names, holders)");
    listGpio->add_flag("--json", line.json, "one JSON array, one object per chip");
    listGpio->footer("Example:\n  overlayd list-gpio");

    const std::vector<std::string> args = withDefaultSubcommand(argc, argv);
    std::vector<std::string> reversed(args.rbegin(), args.rend()); // CLI11 parses a vector back to front
    try {
        app.parse(reversed);
    } catch (const CLI::ParseError &error) {
        line.command = Command::Exit;
        line.exitStatus = app.exit(error);
        return line;
    }
    if (!logLevel.empty()) {
        LogLevel level{};
        parseLogLevel(logLevel, level);
        line.logLevel = level;
    }
    line.command = check->parsed()       ? Command::CheckConfig
                   : project->parsed()   ? Command::Project
                   : render->parsed()    ? Command::Render
                   : list->parsed()      ? Command::ListCameras
                   : listGpio->parsed()  ? Command::ListGpio
                   : unproject->parsed() ? Command::Unproject
                   : solve->parsed()     ? Command::SolvePose
                                         : Command::Run;
    return line;
}

} // namespace overlayd
