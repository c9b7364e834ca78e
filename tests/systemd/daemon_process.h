// SPDX-License-Identifier: Apache-2.0
// DaemonProcess: the real overlayd binary run as systemd would run it (own environment, signals, exit status).
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace overlayd::test {

class DaemonProcess
{
public:
    // Starts `binary args...` with the test's environment minus systemd's variables, plus `environment`.
    // stdout and stderr go to `logPath` (shown when a test fails).
    DaemonProcess(const std::string &binary, const std::vector<std::string> &args,
                  const std::map<std::string, std::string> &environment, std::filesystem::path logPath);
    // Kills (SIGKILL) and reaps a daemon that is still running.
    ~DaemonProcess();
    DaemonProcess(const DaemonProcess &) = delete;
    DaemonProcess &operator=(const DaemonProcess &) = delete;

    pid_t pid() const { return pid_; }
    bool started() const { return pid_ > 0; }
    bool running();
    void signal(int number) const;
    // The wait status once it has exited, or nothing if it is still running after `timeout`.
    std::optional<int> wait(std::chrono::milliseconds timeout);
    std::string log() const;

private:
    pid_t pid_ = -1;
    std::optional<int> status_;
    std::filesystem::path logPath_;
};

} // namespace overlayd::test
