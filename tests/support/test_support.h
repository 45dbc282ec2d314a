// Helpers shared by limn's tests: paths to the test models and built tools, running a tool as
// a subprocess (the way users and Makefiles run it), and scratch directories.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace limn::test {

// tests/data: the meshes and textures the tests read, carried by the repository (its README says
// where each came from and under which licence).
std::filesystem::path dataDir();
std::filesystem::path modelPath(const std::string& relative); // dataDir()/relative
// The directory the tools are built into (<build>/bin).
std::filesystem::path binDir();
std::filesystem::path tool(const std::string& name); // binDir()/name

struct RunResult {
    int exitCode = -1;
    std::string out; // stdout
    std::string err; // stderr
};

// Runs `argv` (argv[0] a path) with `input` on stdin, capturing stdout and stderr. No shell.
RunResult run(const std::vector<std::string>& argv, const std::string& input = {});

// A fresh directory under the system temp dir, removed when the object dies.
class ScratchDir {
public:
    ScratchDir();
    ~ScratchDir();
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

std::string readFile(const std::filesystem::path& path);
// The names of the entries of `dir`, sorted.
std::vector<std::string> filesIn(const std::filesystem::path& dir);
// The .obj meshes of dataDir()/folder (e.g. "osd/catmark": every catmark shape), sorted.
std::vector<std::filesystem::path> objModelsIn(const std::string& folder);
std::vector<uint8_t> readBytes(const std::filesystem::path& path);
void writeFile(const std::filesystem::path& path, const std::string& contents);

// Readers for the flat JSON objects limn's tools print (no nesting beyond one level of objects
// of integers): the integer value of "key", or "key"'s object as a map. Throw when absent, so a
// renamed field fails the test instead of reading as 0.
long long jsonInt(const std::string& json, const std::string& key);
std::map<int, long long> jsonIntMap(const std::string& json, const std::string& key);

} // namespace limn::test
