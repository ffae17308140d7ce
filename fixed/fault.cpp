// fault.cpp — the default fixed-point fault handler (see fault.h).
#include "fixed/fault.h"

#include <cstdio>
#include <cstdlib>

namespace tandem {
namespace {

void default_fixed_fault_handler(FixedFault fault, const char* operation) {
  std::fprintf(stderr, "tandem: fixed-point %s in %s\n", fixed_fault_name(fault), operation);
  std::abort();
}

std::atomic<FixedFaultHandler> g_handler{&default_fixed_fault_handler};

}  // namespace

const char* fixed_fault_name(FixedFault fault) {
  switch (fault) {
    case FixedFault::overflow: return "overflow";
    case FixedFault::divide_by_zero: return "division by zero";
    case FixedFault::out_of_range: return "out-of-range conversion";
    case FixedFault::domain: return "domain error";
  }
  return "fault";
}

FixedFaultHandler set_fixed_fault_handler(FixedFaultHandler handler) {
  if (handler == nullptr) handler = &default_fixed_fault_handler;
  return g_handler.exchange(handler);
}

void report_fixed_fault(FixedFault fault, const char* operation) {
  g_handler.load()(fault, operation);
}

}  // namespace tandem
