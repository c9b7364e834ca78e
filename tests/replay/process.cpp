// Starting and polling a long-running `overlayd run`.
#include "process.h"

#include <thread>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "harness.h"

namespace overlayd::replay {

pid_t startDaemon(const std::string &dir, const std::string &config)
{
    const pid_t pid = fork();
    if (pid == 0) {
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
    return pid;
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

} // namespace overlayd::replay
