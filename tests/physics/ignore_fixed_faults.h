// ignore_fixed_faults.h — a scoped fixed-point fault handler that ignores
// every fault, for tests that compare saturating results on raw extremes:
// builds that report range faults (debug, sanitizers) must not abort there.
#pragma once

#include "fixed/fault.h"

namespace tandem::test_support {

/// Installs a handler that ignores faults; restores the previous one on exit.
struct IgnoreFixedFaults {
  FixedFaultHandler old = set_fixed_fault_handler([](FixedFault, const char*) {});
  ~IgnoreFixedFaults() { set_fixed_fault_handler(old); }
  IgnoreFixedFaults() = default;
  IgnoreFixedFaults(const IgnoreFixedFaults&) = delete;
  IgnoreFixedFaults& operator=(const IgnoreFixedFaults&) = delete;
};

}  // namespace tandem::test_support
