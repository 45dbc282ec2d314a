#include "test_support.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <poll.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

namespace limn::test {

std::filesystem::path dataDir() { return LIMN_TEST_DATA_DIR; }
std::filesystem::path modelPath(const std::string& relative) { return dataDir() / relative; }
std::filesystem::path binDir() { return LIMN_BIN_DIR; }
std::filesystem::path tool(const std::string& name) { return binDir() / name; }

RunResult run(const std::vector<std::string>& argv, const std::string& input) {
    int inPipe[2], outPipe[2], errPipe[2];
    if (pipe(inPipe) || pipe(outPipe) || pipe(errPipe)) throw std::runtime_error("pipe failed");
    pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        dup2(inPipe[0], 0);
        dup2(outPipe[1], 1);
        dup2(errPipe[1], 2);
        for (int fd : {inPipe[0], inPipe[1], outPipe[0], outPipe[1], errPipe[0], errPipe[1]}) close(fd);
        std::vector<char*> args;
        for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        execv(args[0], args.data());
        std::fprintf(stderr, "exec %s: %s\n", args[0], std::strerror(errno));
        _exit(127);
    }
    close(inPipe[0]);
    close(outPipe[1]);
    close(errPipe[1]);
    fcntl(inPipe[1], F_SETFL, O_NONBLOCK);
    RunResult r;
    size_t written = 0;
    bool inOpen = true;
    if (input.empty()) {
        close(inPipe[1]);
        inOpen = false;
    }
    bool outOpen = true, errOpen = true;
    char buf[65536];
    while (outOpen || errOpen) {
        pollfd fds[3];
        int n = 0;
        if (outOpen) fds[n++] = {outPipe[0], POLLIN, 0};
        if (errOpen) fds[n++] = {errPipe[0], POLLIN, 0};
        if (inOpen) fds[n++] = {inPipe[1], POLLOUT, 0};
        if (poll(fds, static_cast<nfds_t>(n), -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        for (int i = 0; i < n; ++i) {
            if (!fds[i].revents) continue;
            if (fds[i].fd == inPipe[1]) {
                ssize_t w = write(inPipe[1], input.data() + written, input.size() - written);
                if (w > 0) written += static_cast<size_t>(w);
                if (w < 0 && errno != EAGAIN) written = input.size();
                if (written == input.size()) {
                    close(inPipe[1]);
                    inOpen = false;
                }
                continue;
            }
            ssize_t got = read(fds[i].fd, buf, sizeof buf);
            if (got <= 0) {
                close(fds[i].fd);
                (fds[i].fd == outPipe[0] ? outOpen : errOpen) = false;
            } else {
                (fds[i].fd == outPipe[0] ? r.out : r.err).append(buf, static_cast<size_t>(got));
            }
        }
    }
    if (inOpen) close(inPipe[1]);
    int status = 0;
    waitpid(pid, &status, 0);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return r;
}

ScratchDir::ScratchDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "limn-test-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
}

ScratchDir::~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

std::vector<std::string> filesIn(const std::filesystem::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::filesystem::path> objModelsIn(const std::string& folder) {
    std::vector<std::filesystem::path> out;
    for (const auto& e : std::filesystem::directory_iterator(modelPath(folder)))
        if (e.path().extension() == ".obj") out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path.string());
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::vector<uint8_t> readBytes(const std::filesystem::path& path) {
    std::string s = readFile(path);
    return {s.begin(), s.end()};
}

void writeFile(const std::filesystem::path& path, const std::string& contents) {
    std::ofstream out(path, std::ios::binary);
    out << contents;
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

static size_t jsonValueStart(const std::string& json, const std::string& key) {
    std::string quoted = "\"" + key + "\":";
    size_t at = json.find(quoted);
    if (at == std::string::npos) throw std::runtime_error("JSON has no field '" + key + "'");
    return at + quoted.size();
}

long long jsonInt(const std::string& json, const std::string& key) {
    size_t at = jsonValueStart(json, key);
    char* end = nullptr;
    long long v = std::strtoll(json.c_str() + at, &end, 10);
    if (end == json.c_str() + at)
        throw std::runtime_error("JSON field '" + key + "' is not an integer");
    return v;
}

std::map<int, long long> jsonIntMap(const std::string& json, const std::string& key) {
    size_t at = jsonValueStart(json, key);
    size_t close = json.find('}', at);
    if (json[at] != '{' || close == std::string::npos)
        throw std::runtime_error("JSON field '" + key + "' is not an object");
    std::map<int, long long> out;
    std::string body = json.substr(at + 1, close - at - 1);
    std::istringstream in(body);
    std::string item;
    while (std::getline(in, item, ',')) {
        int k = 0;
        long long v = 0;
        if (std::sscanf(item.c_str(), "\"%d\":%lld", &k, &v) != 2)
            throw std::runtime_error("JSON field '" + key + "' has a bad entry: " + item);
        out[k] = v;
    }
    return out;
}

} // namespace limn::test
