// cmd_bench.cpp — `tandem bench`: the physics benchmark suite of tools/bench
// (suite.h) from the command line.
//
//   tandem bench [SCENES...] [--runs R] [--steps S] [--broadphase naive,sap,grid,tree|all]
//                [--peers] [--csv FILE] [--json FILE] [--svg FILE] ...
//
// Box2D 2.4 and Chipmunk2D are linked into `tandem` only when the build has
// TANDEM_BUILD_BENCH=ON (tools/bench/CMakeLists.txt picks peers.cpp or
// peers_none.cpp); without them --peers says so and runs Tandem alone. The
// tandem_bench_physics driver runs the same code with the peers on.
#include "cli.h"

#include <memory>

#include "../bench/bench_options.h"

namespace tandem::cli {

void register_bench_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands) {
  CLI::App* sub = app.add_subcommand(
      "bench", "Benchmark scenes (circles-N, pyramid-B, rain-N) in Tandem's broad phases, optionally against peers");
  auto bench_options = std::make_shared<bench::BenchOptions>();
  bench::add_bench_options(*sub, bench_options.get(), false);
  const GlobalOptions* global = &options;
  commands->push_back({sub, [bench_options, global]() {
                         bench::BenchOptions o = *bench_options;
                         o.quiet = o.quiet || global->quiet;
                         return bench::run_bench_suite(o);
                       }});
}

}  // namespace tandem::cli
