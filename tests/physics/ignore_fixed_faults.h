// ignore_fixed_faults.h — scoped fixed-point fault handlers for tests: one
// that ignores every fault (tests that compare saturating results on raw
// extremes: builds that report range faults, debug and sanitizers, must not
// abort there) and one that counts them (tests that assert none occurred).
#pragma once

#include <cstdint>

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

/// Installs a handler that counts faults (builds with fault checks; others
/// report none); restores the previous one on exit. One at a time.
struct CountFixedFaults {
  static inline int64_t counted = 0;
  FixedFaultHandler old = set_fixed_fault_handler([](FixedFault, const char*) { ++counted; });
  CountFixedFaults() { counted = 0; }
  ~CountFixedFaults() { set_fixed_fault_handler(old); }
  CountFixedFaults(const CountFixedFaults&) = delete;
  CountFixedFaults& operator=(const CountFixedFaults&) = delete;
  /// Faults reported since construction.
  int64_t count() const { return counted; }
};

}  // namespace tandem::test_support
