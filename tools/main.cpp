// SPDX-License-Identifier: Apache-2.0
// overlayd: the camera-overlay daemon and its tools. Exceptions are start-up failures only, caught here once.
#include <csignal>
#include <cstdio>
#include <exception>

#include "base/logger.h"
#include "stream/engine_loader.h"
#include "tools/cli.h"
#include "tools/commands.h"
#include "tools/early_signals.h"

int main(int argc, char **argv)
{
    using namespace overlayd;
    // A sink whose reader went away (`overlayd run | ffplay -`, ffplay closed) must fail as an I/O error on that
    // sink, not kill the daemon and every other sink with it.
    std::signal(SIGPIPE, SIG_IGN);
    try {
        const CommandLine line = parseCommandLine(argc, argv);
        if (line.command != Command::Run)
            restoreInheritedSignalMask(); // the tools stop on a signal as any tool does; only `run` reads them
        if (line.command == Command::Exit)
            return line.exitStatus;
        Logger logger = Logger::forStderr();
        if (line.logLevel)
            logger.setLevel(*line.logLevel);
        // The config loader refuses encoded sinks whose module cannot be loaded, as `run` would fail to start them.
        if (line.command == Command::CheckConfig || line.command == Command::Run)
            requireStreamModule();
        switch (line.command) {
        case Command::CheckConfig:
            return checkConfigCommand(line.configPath);
        case Command::Project:
            return projectCommand(line.configPath, line.json, line.coordinates, line.pointsPath, line.size, logger);
        case Command::ListCameras:
            return listCamerasCommand(line.json);
        case Command::Unproject:
            return unprojectCommand(line.configPath, line.json, line.plane, line.coordinates, logger);
        case Command::SolvePose:
            return solvePoseCommand(line.configPath, line.pointsPath, line.solver, line.write, logger);
        case Command::ListGpio:
            return listGpioCommand(line.json);
        case Command::Render:
            return renderCommand(line.configPath, line.frames, line.output, line.logLevel, logger);
        case Command::Run:
        case Command::Exit:
            break;
        }
        return runCommand(DaemonOptions{line.configPath, line.logLevel, line.frames}, logger);
    } catch (const std::exception &error) {
        std::fprintf(stderr, "overlayd: fatal: %s\n", error.what());
        return kExitFailure;
    }
}
