// fault.h — what happens when a fixed-point operation leaves its range.
//
// Every operation has a defined result in every build (saturation, or the
// documented value for division by zero); see fixed.h. In addition, when
// TANDEM_FIXED_CHECKS is 1 (the default in builds without NDEBUG) the
// operation reports the fault to a handler that names it. The default handler
// prints "tandem: fixed-point <fault> in <operation>" to stderr and aborts, so
// a debug build stops at the first overflow. Tests install their own handler
// to count faults instead.
#pragma once

#include <atomic>

#if !defined(TANDEM_FIXED_CHECKS)
#if defined(NDEBUG)
#define TANDEM_FIXED_CHECKS 0
#else
#define TANDEM_FIXED_CHECKS 1
#endif
#endif

namespace tandem {

/// The kinds of range fault a fixed-point operation can report.
enum class FixedFault : int {
  overflow,        ///< the exact result is outside the format; saturated
  divide_by_zero,  ///< divisor was zero; result is 0 for 0/0, else ±max
  out_of_range,    ///< a conversion's input does not fit; saturated
  domain,          ///< input outside the function's domain (sqrt of < 0)
};

/// Returns a short lower-case name for a fault ("overflow", ...).
const char* fixed_fault_name(FixedFault fault);

/// Called on a fault with the fault and the operation's name, for example
/// (FixedFault::overflow, "Q32.32 multiply"). Must return normally or abort;
/// the operation then returns its defined, saturated result.
using FixedFaultHandler = void (*)(FixedFault fault, const char* operation);

/// Installs a handler (nullptr restores the default) and returns the old one.
/// Thread-safe; the handler itself must be.
FixedFaultHandler set_fixed_fault_handler(FixedFaultHandler handler);

/// Reports a fault to the installed handler. Out of line and cold: only ever
/// called on the error path, and only when TANDEM_FIXED_CHECKS is 1.
[[gnu::cold]] void report_fixed_fault(FixedFault fault, const char* operation);

}  // namespace tandem

/// Reports a fault when checks are on; compiles to nothing otherwise.
#if TANDEM_FIXED_CHECKS
#define TANDEM_FIXED_FAULT(fault, operation) ::tandem::report_fixed_fault((fault), (operation))
#else
#define TANDEM_FIXED_FAULT(fault, operation) ((void)0)
#endif
