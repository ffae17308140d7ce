// bench_physics_main.cpp — tandem_bench_physics: the physics benchmark suite
// against Box2D 2.4 and Chipmunk2D (suite.h). Same options as `tandem bench`,
// except that the peers run unless --no-peers is given.
//
//   tandem_bench_physics [SCENES...] [--runs R] [--runs-large R] [--steps S]
//       [--warmup W] [--broadphase naive,sap,grid,tree|all] [--no-peers]
//       [--naive-max N] [--csv FILE] [--json FILE] [--svg FILE]
#include <CLI/CLI.hpp>

#include "bench_options.h"

int main(int argc, char** argv) {
  CLI::App app{"Tandem physics benchmark: circles-N, pyramid-B and rain-N in Tandem (each broad phase), "
               "Box2D 2.4 and Chipmunk2D"};
  tandem::bench::BenchOptions options;
  tandem::bench::add_bench_options(app, &options, true);
  app.add_flag("-q,--quiet", options.quiet, "no progress lines on stderr");
  CLI11_PARSE(app, argc, argv);
  return tandem::bench::run_bench_suite(options);
}
