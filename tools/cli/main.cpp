// tandem — the command line (placeholder until the demo lands).
#include <CLI/CLI.hpp>
#include <cstdio>
#include "fixed/fixed.h"
int main(int argc, char** argv) {
  CLI::App app{"tandem"};
  CLI11_PARSE(app, argc, argv);
  using namespace tandem::literals;
  std::printf("%s\n", tandem::to_string(1.5_q32).c_str());
  return 0;
}
