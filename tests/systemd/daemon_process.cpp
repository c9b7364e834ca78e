// SPDX-License-Identifier: Apache-2.0
// DaemonProcess: posix_spawn with an explicit environment, and a polling wait with a deadline.
#include "daemon_process.h"

#include <csignal>
#include <fcntl.h>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <sys/wait.h>
#include <thread>

extern char **environ;

namespace overlayd::test {

namespace {

std::vector<std::string> childEnvironment(const std::map<std::string, std::string> &extra)
{
    std::vector<std::string> result;
    for (char **entry = environ; *entry; ++entry) {
        std::string variable = *entry;
        std::string name = variable.substr(0, variable.find('='));
        if (name != "NOTIFY_SOCKET" && name != "WATCHDOG_USEC" && name != "WATCHDOG_PID" && !extra.count(name))
            result.push_back(variable);
    }
    for (const auto &[name, value] : extra)
        result.push_back(name + "=" + value);
    return result;
}

std::vector<char *> pointers(std::vector<std::string> &strings)
{
    std::vector<char *> result;
    for (auto &s : strings)
        result.push_back(s.data());
    result.push_back(nullptr);
    return result;
}

} // namespace

DaemonProcess::DaemonProcess(const std::string &binary, const std::vector<std::string> &args,
                             const std::map<std::string, std::string> &environment, std::filesystem::path logPath)
    : logPath_(std::move(logPath))
{
    std::vector<std::string> argv{binary};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<std::string> envp = childEnvironment(environment);
    auto argvPointers = pointers(argv);
    auto envpPointers = pointers(envp);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, logPath_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    if (posix_spawn(&pid_, binary.c_str(), &actions, nullptr, argvPointers.data(), envpPointers.data()) != 0)
        pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
}

DaemonProcess::~DaemonProcess()
{
    if (running()) {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
    }
}

bool DaemonProcess::running()
{
    if (pid_ <= 0 || status_)
        return false;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_)
        status_ = status;
    return !status_;
}

void DaemonProcess::signal(int number) const
{
    if (pid_ > 0 && !status_)
        kill(pid_, number);
}

std::optional<int> DaemonProcess::wait(std::chrono::milliseconds timeout)
{
    auto end = std::chrono::steady_clock::now() + timeout;
    while (running() && std::chrono::steady_clock::now() < end)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return status_;
}

std::string DaemonProcess::log() const
{
    std::ifstream in(logPath_);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

} // namespace overlayd::test
