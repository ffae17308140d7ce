// A consumer of an installed Tandem: includes the installed headers, links the
// installed static library (to_string and the fault handler live in it) and
// checks a few exact results. Exit status 0 when all hold.
#include <cstdio>
#include <string>

#include "fixed/fault.h"
#include "fixed/fixed.h"

namespace {
int g_faults = 0;
void count_fault(tandem::FixedFault, const char*) { ++g_faults; }
}  // namespace

int main() {
  using namespace tandem::literals;
  int failures = 0;
  auto check = [&failures](bool ok, const char* what) {
    if (!ok) {
      std::printf("consumer: FAILED %s\n", what);
      ++failures;
    }
  };
  const tandem::Q32 a = 1.5_q32, b = -2.25_q32;
  check(a * b == -3.375_q32, "1.5 * -2.25 == -3.375");
  check(tandem::to_string(a * b) == "-3.375", "to_string(-3.375)");
  check((1_q32 / 3_q32).raw == 1431655765, "1/3 rounds to nearest (0x55555555)");
  check(tandem::parse_q32("0.5").value == tandem::Q32::half(), "parse_q32(\"0.5\")");
  // Saturation returns ±max in every build; the handler is called in builds
  // with checks on (library and consumer agree: TANDEM_FIXED_CHECKS).
  const tandem::FixedFaultHandler old = tandem::set_fixed_fault_handler(count_fault);
  check(tandem::Q32::max() + tandem::Q32::one() == tandem::Q32::max(), "max + 1 saturates");
  check(g_faults == (TANDEM_FIXED_CHECKS ? 1 : 0), "fault reported iff checks are on");
  tandem::set_fixed_fault_handler(old);
  std::printf("consumer: %s (%d failures), 1.5 * -2.25 = %s\n", failures == 0 ? "ok" : "FAILED", failures,
              tandem::to_string(a * b).c_str());
  return failures == 0 ? 0 : 1;
}
