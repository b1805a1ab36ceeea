// The wiping study's sweep (docs/fidelity.md): its wall time with 1 worker process and with N,
// each repeated, and whether every worker count gives the same cells (it must: each cell is a
// fresh simulation). A driver, not a Google Benchmark: one sweep takes seconds.
//   teleop_wiping_sweep_bench [--study wiping] [--jobs 1,2] [--repeats 3]
#include <sys/resource.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "teleop/common/data_paths.h"
#include "teleop/experiment/wiping_study.h"

namespace {

// CPU time of the finished worker processes so far (user + system)
double children_cpu_s() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"the wiping study's sweep: wall time with 1 worker process against N", "teleop_wiping_sweep_bench"};
  std::string study = "wiping";
  std::vector<int> jobs{1, 2};
  int repeats = 3;
  app.add_option("--study", study, "study YAML file, or its name in config/experiments");
  app.add_option("--jobs", jobs, "worker counts to time (comma-separated)")->delimiter(',');
  app.add_option("--repeats", repeats, "sweeps per worker count")->check(CLI::Range(1, 100));
  CLI11_PARSE(app, argc, argv);

  teleop::experiment::WipingStudyConfig config =
      teleop::experiment::load_wiping_study(teleop::resolve_config("experiments", study));
  const size_t cells = config.wiper_angle.values.size() * config.panel_height.values.size();
  std::string reference;
  double one_worker_s = 0.0;
  // cpu/wall: how many cores the workers really had (about 1 on a loaded machine, whatever jobs is)
  std::printf("%zu cells per sweep, %d repeats; speedup against the first worker count\n%6s %10s %10s %10s %8s %9s\n",
              cells, repeats, "jobs", "min_s", "median_s", "max_s", "speedup", "cpu/wall");
  for (int n : jobs) {
    config.jobs = n;
    std::vector<double> wall;
    const double cpu_before = children_cpu_s();
    for (int r = 0; r < repeats; ++r) {
      const auto start = std::chrono::steady_clock::now();
      const auto result = teleop::experiment::run_wiping_sweep(config);
      wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      const std::string csv = teleop::experiment::format_wiping_csv(result);
      if (reference.empty()) reference = csv;
      if (csv != reference) {
        std::fprintf(stderr, "jobs %d, repeat %d: the cells differ from the first sweep's\n", n, r + 1);
        return 1;
      }
    }
    double wall_total = 0.0;
    for (double w : wall) wall_total += w;
    const double cpu = children_cpu_s() - cpu_before;
    if (one_worker_s == 0.0) one_worker_s = median(wall);
    std::printf("%6d %10.3f %10.3f %10.3f %8.2f %9.2f\n", n, *std::min_element(wall.begin(), wall.end()), median(wall),
                *std::max_element(wall.begin(), wall.end()), one_worker_s / median(wall), cpu / wall_total);
  }
  std::printf("every sweep's cells identical: yes\n");
  return 0;
}
