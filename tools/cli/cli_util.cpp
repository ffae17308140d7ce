// cli_util.cpp — see cli_util.h.
#include "cli_util.h"

#include <unistd.h>

#include <cinttypes>
#include <cstdio>

namespace tandem::cli {

ProgressBar::ProgressBar(const char* label, bool off, const char* unit)
    : label_(label), unit_(unit), enabled_(!off && isatty(STDERR_FILENO) != 0) {}

void ProgressBar::update(uint64_t done, uint64_t total) {
  if (!enabled_ || total == 0) return;
  const auto now = Clock::now();
  if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  shown_ = true;
  const uint64_t width = 40;
  const uint64_t filled = (done > total ? total : done) * width / total;
  std::fprintf(stderr, "\r%s%s[%s%s] %3d%% %s %" PRIu64 "/%" PRIu64, label_, *label_ != '\0' ? " " : "",
               std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(),
               static_cast<int>(done * 100 / total), unit_, done, total);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (shown_) std::fprintf(stderr, "\r%s\r", std::string(80, ' ').c_str());
  shown_ = false;
}

int fail(const char* command, const std::string& message) {
  std::fprintf(stderr, "tandem %s: %s\n", command, message.c_str());
  return 2;
}

void add_output_flags(CLI::App* command, bool* json, bool* quiet, const char* quiet_help) {
  command->add_flag("--json", *json, "machine-readable output on stdout");
  command->add_flag("--quiet,-q", *quiet, quiet_help);
}

}  // namespace tandem::cli
