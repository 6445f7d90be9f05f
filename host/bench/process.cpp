#include "bench/process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench/random_spheres.hpp"
#include "bench/support.hpp"
#include "scene/json_scene_loader.hpp"

extern char** environ;

namespace vkrt::bench {
namespace {

struct Run {
    int status = 0;
    double seconds = 0.0;
};

// Runs argv with its standard output discarded and its standard error kept in
// stderr_file; the wall clock from spawn to exit.
Run run_process(const std::vector<std::string>& argv, const std::string& stderr_file) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const auto start = std::chrono::steady_clock::now();
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) throw std::runtime_error(fmt::format("cannot run {}: {}", argv[0], std::strerror(spawned)));
    Run run;
    while (waitpid(pid, &run.status, 0) < 0) {
        if (errno != EINTR) throw std::runtime_error(fmt::format("waiting for {}: {}", argv[0], std::strerror(errno)));
    }
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return run;
}

std::string exit_reason(int status) {
    if (WIFEXITED(status)) return fmt::format("exit status {}", WEXITSTATUS(status));
    if (WIFSIGNALED(status)) return fmt::format("killed by signal {}", WTERMSIG(status));
    return "did not exit";
}

// The last line the child wrote to standard error: its error message.
std::string last_line(const std::string& file) {
    std::ifstream in(file);
    std::string line, last;
    while (std::getline(in, line)) {
        if (!line.empty()) last = line;
    }
    return last;
}

struct Samples {
    std::vector<double> whole, load, setup, render, peak;
};

}  // namespace

std::vector<ProcessRow> measure_processes(const ProcessPlan& plan, const std::vector<ProcessScene>& scenes) {
    std::vector<ProcessRow> rows;
    std::vector<Samples> samples;
    for (const ProcessScene& s : scenes) {
        for (const std::string& b : plan.backends) {
            rows.push_back(ProcessRow{s.label, b, {}, 0, 0, 0, 0, 0});
            samples.emplace_back();
        }
    }
    const std::string image = plan.scratch + "/process.png";
    const std::string stats_file = plan.scratch + "/process.json";
    const std::string errors = plan.scratch + "/process.stderr";
    for (std::uint32_t run = 0; run < plan.runs; ++run) {
        std::size_t i = 0;
        for (const ProcessScene& s : scenes) {
            for (const std::string& b : plan.backends) {
                ProcessRow& row = rows[i];
                Samples& got = samples[i++];
                if (!row.failed.empty()) continue;
                std::vector<std::string> argv = {plan.executable, "render", s.file, "-q", "--backend", b,
                                                 "-o", image, "--stats", stats_file};
                if (b == "vulkan" && !plan.device.empty()) argv.insert(argv.end(), {"--device", plan.device});
                std::filesystem::remove(stats_file);
                const Run r = run_process(argv, errors);
                if (r.status != 0) {
                    const std::string why = last_line(errors);
                    row.failed = fmt::format("failed ({}{}{})", exit_reason(r.status), why.empty() ? "" : ": ", why);
                    continue;
                }
                double peak = 0.0;
                try {
                    const nlohmann::json stats = nlohmann::json::parse(std::ifstream(stats_file));
                    const nlohmann::json& sec = stats.at("seconds");
                    got.load.push_back(sec.at("load").get<double>());
                    got.setup.push_back(sec.at("flatten").get<double>() + sec.at("setup").get<double>());
                    got.render.push_back(sec.at("render").get<double>());
                    peak = stats.at("memory").at("peak_resident_bytes").get<double>() / (1 << 20);
                } catch (const nlohmann::json::exception& e) {
                    row.failed = fmt::format("failed (its stats file: {})", e.what());
                    continue;
                }
                got.whole.push_back(r.seconds);
                got.peak.push_back(peak);
                if (!plan.quiet) {
                    fmt::print(stderr, "bench: {}: vkrt render --backend {}, run {}/{}: {:.2f} s, {:.0f} MiB\n",
                               s.label, b, run + 1, plan.runs, r.seconds, peak);
                }
            }
        }
    }
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (!rows[i].failed.empty()) continue;
        rows[i].whole_seconds = median(samples[i].whole);
        rows[i].load_seconds = median(samples[i].load);
        rows[i].setup_seconds = median(samples[i].setup);
        rows[i].render_seconds = median(samples[i].render);
        rows[i].peak_mib = median(samples[i].peak);
    }
    return rows;
}

void write_process_markdown(std::ostream& out, const std::vector<ProcessRow>& rows) {
    out << "| scene | backend | whole process s | load s | set-up s | render s | peak MiB |\n"
           "|---|---|---:|---:|---:|---:|---:|\n";
    for (const ProcessRow& r : rows) {
        if (!r.failed.empty()) {
            out << fmt::format("| {} | {} | {} | – | – | – | – |\n", r.scene, r.backend, r.failed);
            continue;
        }
        out << fmt::format("| {} | {} | {} | {} | {} | {} | {:.0f} |\n", r.scene, r.backend,
                           significant(r.whole_seconds), significant(r.load_seconds), significant(r.setup_seconds),
                           significant(r.render_seconds), r.peak_mib);
    }
}

std::string explicit_spheres_json(std::uint64_t count) {
    const std::string generated = random_spheres_scene(count);
    const Scene scene = parse_json_scene(generated, "random_spheres.json");
    const std::string::size_type objects = generated.find("\"objects\"");
    if (objects == std::string::npos) throw std::logic_error("random_spheres_scene has no objects");
    std::string text = generated.substr(0, objects) + "\"objects\": [\n";
    text.reserve(scene.spheres.size() * 110);
    for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
        const Sphere& s = scene.spheres[i];
        text += fmt::format(R"({}    {{ "type": "sphere", "center": [{:.9g}, {:.9g}, {:.9g}], "radius": {:.9g}, "material": "{}" }})",
                            i == 0 ? "" : ",\n", s.center.x, s.center.y, s.center.z, s.radius,
                            scene.materials[s.material].name);
    }
    return text + "\n  ]\n}\n";
}

}  // namespace vkrt::bench
