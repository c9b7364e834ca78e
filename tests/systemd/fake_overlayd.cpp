// SPDX-License-Identifier: Apache-2.0
// fake_overlayd: a stand-in daemon that checks the end-to-end tests themselves (run them with
// OVERLAYD_TEST_DAEMON=<this>); FAKE_OVERLAYD_BUG=<name> makes it break one rule, and the tests must then fail.
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <poll.h>
#include <sstream>
#include <string>
#include <sys/signalfd.h>
#include <sys/timerfd.h>
#include <unistd.h>

#include "daemon/systemd_notify.h"

namespace {

struct FakeConfig {
    bool valid = false;
    bool synthetic = false;
    unsigned stallAfter = 0;
};

FakeConfig readConfig(const std::string &path)
{
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    FakeConfig config;
    config.synthetic = s.find("kind = \"synthetic\"") != std::string::npos;
    config.valid = config.synthetic || s.find("kind = \"v4l2\"") != std::string::npos;
    if (auto at = s.find("stall_after_frames = "); at != std::string::npos)
        config.stallAfter = unsigned(std::stoul(s.substr(at + 21)));
    return config;
}

int timer(long periodNs)
{
    int fd = timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC);
    itimerspec spec{{0, periodNs}, {0, periodNs}};
    timerfd_settime(fd, 0, &spec, nullptr);
    return fd;
}

bool bug(const char *name)
{
    const char *value = std::getenv("FAKE_OVERLAYD_BUG");
    return value && std::string(value) == name;
}

} // namespace

int main(int argc, char **argv)
{
    if (argc < 4)
        return 2;
    const std::string path = argv[3];
    FakeConfig config = readConfig(path);
    auto notifier = overlayd::SystemdNotifier::fromEnvironment();
    if (!config.valid)
        return 1;

    sigset_t signals;
    sigemptyset(&signals);
    for (int s : {SIGHUP, SIGTERM, SIGINT})
        sigaddset(&signals, s);
    sigprocmask(SIG_BLOCK, &signals, nullptr);
    pollfd fds[3] = {{signalfd(-1, &signals, SFD_CLOEXEC), POLLIN, 0}, {timer(33333333), POLLIN, 0}, {-1, POLLIN, 0}};
    auto interval = notifier->watchdogInterval();
    if (interval)
        fds[2].fd = timer(long(interval->count()) * 1000);
    if (bug("ready-at-start"))
        notifier->ready();
    if (!config.synthetic)
        notifier->status("waiting for the camera: no such device, retry in 1 s");

    unsigned frames = 0, sincePet = 0;
    bool ready = false;
    for (;;) {
        poll(fds, 3, -1);
        uint64_t ticks = 0;
        if (fds[1].revents & POLLIN) {
            (void)!read(fds[1].fd, &ticks, sizeof(ticks));
            if (config.synthetic && (config.stallAfter == 0 || frames < config.stallAfter || bug("never-stall"))) {
                ++frames, ++sincePet;
                if (!ready) {
                    notifier->ready();
                    notifier->status("streaming 320x240 YUYV 30.0 fps, 0 drops");
                }
                ready = true;
            }
        }
        if (fds[2].fd >= 0 && (fds[2].revents & POLLIN)) {
            (void)!read(fds[2].fd, &ticks, sizeof(ticks));
            if (sincePet > 0 || bug("pet-always"))
                notifier->watchdog();
            sincePet = 0;
        }
        if (fds[0].revents & POLLIN) {
            signalfd_siginfo info{};
            (void)!read(fds[0].fd, &info, sizeof(info));
            if (info.ssi_signo != SIGHUP) {
                if (!bug("no-stopping"))
                    notifier->stopping();
                return 0;
            }
            if (!bug("no-reloading"))
                notifier->reloading();
            FakeConfig next = readConfig(path);
            if (next.valid)
                config = next;
            else if (!bug("silent-reject"))
                notifier->status("reload refused, kept the previous config");
            notifier->ready();
        }
    }
}
