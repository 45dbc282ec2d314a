// Sequences in one run against separate commands, wall time of whole limn-render
// processes, interleaved in rounds, medians:
//   turntable   one `--turntable 36` run vs 36 runs with `--view AZ,EL` (spot, depth 4, 640x480)
//   frames      one `--frames` run over 100 frames of the twisting torus vs the same command over
//               its first frame only: (T100 - T1) / 99 is the time a frame adds, compared with
//               the `--bench` frame of one mesh (cpu_ms: upload, passes, readback; no encoding)
// Usage: bench_sequence [--rounds R] [SPOT.obj]   (tools from this binary's folder)
// Prints one JSON line per measurement and the ratios.
#include "mesh/examples.h"
#include "mesh/obj.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

double seconds(const std::string& command) {
    const auto start = std::chrono::steady_clock::now();
    if (std::system(command.c_str()) != 0) {
        std::fprintf(stderr, "bench_sequence: failed: %s\n", command.c_str());
        std::exit(1);
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

std::string capture(const std::string& command) {
    std::string out;
    if (FILE* p = popen(command.c_str(), "r")) {
        char buf[4096];
        for (size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
        pclose(p);
    }
    return out;
}

double jsonNumber(const std::string& json, const std::string& key) {
    const size_t at = json.find("\"" + key + "\":");
    return at == std::string::npos ? 0 : std::atof(json.c_str() + at + key.size() + 3);
}

} // namespace

int main(int argc, char** argv) {
    int rounds = 3;
    std::string spot = "tests/data/quad/spot_control_mesh.obj";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--rounds" && i + 1 < argc) rounds = std::max(1, std::atoi(argv[++i]));
        else spot = a;
    }
    const fs::path bin = fs::canonical("/proc/self/exe").parent_path();
    const fs::path tmp = fs::temp_directory_path() / ("limn_bench_sequence_" + std::to_string(::getpid()));
    fs::create_directories(tmp / "twist");
    const std::string render = (bin / "limn-render").string() + " -q", tables = (bin / "limn-tables").string() + " -q";
    // Inputs: spot's depth-4 tables; 100 frames of the twisting torus and tables from frame 0.
    seconds(tables + " --depth 4 " + spot + " -o " + (tmp / "spot.limn").string());
    for (int k = 0; k < 100; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "twist_%04d.obj", k);
        std::ofstream(tmp / "twist" / name) << limn::writeObj(limn::makeTwistingTorus(24, 12, k, 100));
    }
    seconds(tables + " --depth 3 " + (tmp / "twist" / "twist_0000.obj").string() + " -o " + (tmp / "twist.limn").string());
    fs::create_directories(tmp / "first");
    fs::copy_file(tmp / "twist" / "twist_0000.obj", tmp / "first" / "twist_0000.obj");

    const std::string spotLimn = (tmp / "spot.limn").string(), out = (tmp / "out").string();
    fs::create_directories(out);
    std::vector<double> oneRun, separate, frames100, frames1, benchFrame;
    for (int r = 0; r < rounds; ++r) {
        oneRun.push_back(seconds(render + " " + spotLimn + " --size 640x480 --turntable 36 -o " + out + "/tt_%02d.png"));
        std::string loop = "set -e; for k in $(seq 0 35); do " + render + " " + spotLimn +
                           " --size 640x480 --view $(( (30 + 10 * k) % 360 )),20 -o " + out + "/single_$k.png; done";
        separate.push_back(seconds("sh -c '" + loop + "'"));
        const std::string twist = render + " " + (tmp / "twist.limn").string() + " --size 640x480 --frames ";
        frames100.push_back(seconds(twist + (tmp / "twist" / "twist_%04d.obj").string() + " -o " + out + "/tw_%04d.png"));
        frames1.push_back(seconds(twist + (tmp / "first" / "twist_%04d.obj").string() + " -o " + out + "/tw1_%04d.png"));
        const std::string json = capture(render + " " + (tmp / "twist.limn").string() + " --size 640x480 --bench 20");
        benchFrame.push_back(jsonNumber(json, "cpu_ms") / 1000);
    }
    const double perFrame = (median(frames100) - median(frames1)) / 99;
    std::printf("{\"bench\":\"turntable\",\"views\":36,\"one_run_s\":%.3f,\"separate_runs_s\":%.3f,"
                "\"separate_over_one_run\":%.2f}\n",
                median(oneRun), median(separate), median(separate) / median(oneRun));
    std::printf("{\"bench\":\"frames\",\"frames\":100,\"run_100_s\":%.3f,\"run_1_s\":%.3f,"
                "\"per_frame_ms\":%.2f,\"bench_frame_ms\":%.2f,\"per_frame_over_bench_frame\":%.2f}\n",
                median(frames100), median(frames1), 1000 * perFrame, 1000 * median(benchFrame),
                perFrame / median(benchFrame));
    fs::remove_all(tmp);
    return 0;
}
