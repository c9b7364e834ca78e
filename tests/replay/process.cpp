// SPDX-License-Identifier: Apache-2.0
// Starting and polling a long-running `overlayd run`.
#include "process.h"

#include <cerrno>
#include <csignal>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "harness.h"

namespace overlayd::test {

pid_t startDaemon(const std::string &dir, const std::string &config, bool blockStopSignals)
{
    // Closed by the exec (O_CLOEXEC): end of file on the read side says the child is overlayd now.
    int execed[2];
    if (pipe2(execed, O_CLOEXEC) != 0)
        return -1;
    const pid_t pid = fork();
    if (pid == 0) {
        close(execed[0]);
        if (blockStopSignals) {
            sigset_t stop;
            sigemptyset(&stop);
            sigaddset(&stop, SIGTERM);
            sigaddset(&stop, SIGINT);
            sigprocmask(SIG_BLOCK, &stop, nullptr);
        }
        if (chdir(dir.c_str()) != 0)
            _exit(127);
        const int err = open("overlayd.stderr", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(err, STDERR_FILENO);
        setenv("JOURNAL_STREAM", "8:12345", 1);
        std::vector<std::string> words = binaryArgv();
        words.insert(words.end(), {"run", "--config", config});
        std::vector<char *> argv;
        for (std::string &word : words)
            argv.push_back(word.data());
        argv.push_back(nullptr);
        execvp(argv[0], argv.data());
        _exit(127);
    }
    close(execed[1]);
    char byte;
    while (read(execed[0], &byte, 1) < 0 && errno == EINTR) {
    }
    close(execed[0]);
    return pid;
}

std::optional<Ending> waitForExit(pid_t pid, std::chrono::milliseconds limit)
{
    const auto deadline = std::chrono::steady_clock::now() + limit;
    int status = 0;
    pid_t done = 0;
    while ((done = waitpid(pid, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (done != pid) {
        kill(pid, SIGKILL);
        waitpid(pid, nullptr, 0);
        return std::nullopt;
    }
    if (WIFEXITED(status))
        return Ending{WEXITSTATUS(status), 0, false};
    return Ending{-1, WIFSIGNALED(status) ? WTERMSIG(status) : 0, WIFSIGNALED(status) && WCOREDUMP(status)};
}

bool waitFor(const std::function<bool()> &condition, std::chrono::seconds limit)
{
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < deadline) {
        if (condition())
            return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return condition();
}

std::string fileText(const std::string &path)
{
    const auto bytes = readFile(path);
    return std::string(bytes.begin(), bytes.end());
}

} // namespace overlayd::test
