// limits.cpp — range checks with messages that name the culprit.
#include "physics/limits.h"

namespace tandem {

bool check_limit(const std::string& what, Q32 value, Q32 lo, Q32 hi, const char* unit, std::string* out_message) {
  if (lo <= value && value <= hi) return true;
  if (out_message) {
    *out_message = what + " " + to_string(value) + " " + unit + " is outside [" + to_string(lo) + ", " +
                   to_string(hi) + "] " + unit;
  }
  return false;
}

}  // namespace tandem
